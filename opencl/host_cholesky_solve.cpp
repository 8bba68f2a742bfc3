#include "opencl/host_cholesky_solve.hpp"

#include "common/errors.hpp"
#include "opencl/device_tuning.hpp"
#include "opencl/flush_denormals.hpp"

#include <Eigen/SparseCholesky>

namespace physarum::opencl {

namespace {

// P S P^-1 = L D L^T, solved in place in a buffer sized once (Eigen's solve() allocates per call).
template <class Decomposition, class Vector>
void permuted_solve(const Decomposition& factor, Vector& permuted, const float* b, float* x, int n) {
  const Eigen::VectorXi& p = factor.permutationP().indices();  // empty: no permutation
  const bool reorder = p.size() == n;
  for (int i = 0; i < n; ++i) permuted[reorder ? p[i] : i] = b[i];
  factor.matrixL().solveInPlace(permuted);
  permuted.array() /= factor.vectorD().array();
  factor.matrixU().solveInPlace(permuted);
  for (int i = 0; i < n; ++i) x[i] = static_cast<float>(permuted[reorder ? p[i] : i]);
}

}  // namespace

struct HostCholeskySolve::Factor {
  FactorPrecision precision;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<float>> single;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> twice;
  Eigen::VectorXf permuted_single;  // P b, then the solution in the factor's order
  Eigen::VectorXd permuted_double;
};

HostCholeskySolve::~HostCholeskySolve() = default;

HostCholeskySolve::HostCholeskySolve(const CsrMatrix& system, FactorPrecision precision, const std::string& what)
    : n_(system.rows), factor_(std::make_unique<Factor>()) {
  Factor& f = *factor_;
  f.precision = precision;
  // S is symmetric, so its CSR rows are its CSC columns. LDL^T factors an indefinite matrix too:
  // positive definite means every pivot > 0.
  bool factored = false;
  if (precision == FactorPrecision::Single) {
    f.single.compute(system.to_eigen().cast<float>());
    factored = f.single.info() == Eigen::Success && (f.single.vectorD().array() > 0.0f).all();
    f.permuted_single.resize(n_);
  } else {
    f.twice.compute(system.to_eigen());
    factored = f.twice.info() == Eigen::Success && (f.twice.vectorD().array() > 0.0).all();
    f.permuted_double.resize(n_);
  }
  if (!factored)
    throw InputError(what + ": the implicit system could not be factorised on the host (not positive definite in " +
                     (precision == FactorPrecision::Single ? "float" : "double") + ")");
}

void HostCholeskySolve::solve(const float* b, float* x) {
  const FlushDenormalsToZero flush;  // decayed fields' tails (opencl/flush_denormals.hpp)
  Factor& f = *factor_;
  if (f.precision == FactorPrecision::Single) permuted_solve(f.single, f.permuted_single, b, x, n_);
  else permuted_solve(f.twice, f.permuted_double, b, x, n_);
}

bool implicit_solve_on_host(const DeviceInfo& device, int vertex_count) {
  return vertex_count <= tuning_for(device).host_implicit_solve_max_vertices;
}

}  // namespace physarum::opencl
