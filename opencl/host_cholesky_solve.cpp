#include "opencl/host_cholesky_solve.hpp"

#include "common/errors.hpp"
#include "opencl/device_tuning.hpp"

#include <Eigen/SparseCholesky>

namespace physarum::opencl {

struct HostCholeskySolve::Factor {
  Eigen::SimplicialLLT<Eigen::SparseMatrix<float>> llt;
  Eigen::VectorXf permuted;  // P b, then the solution in the factor's order
};

HostCholeskySolve::~HostCholeskySolve() = default;

HostCholeskySolve::HostCholeskySolve(const CsrMatrix& system, const std::string& what)
    : n_(system.rows), factor_(std::make_unique<Factor>()) {
  // S is symmetric, so its CSR rows are its CSC columns.
  const Eigen::SparseMatrix<float> s = system.to_eigen().cast<float>();
  factor_->llt.compute(s);
  if (factor_->llt.info() != Eigen::Success)
    throw InputError(what + ": the implicit system could not be factorised on the host (LLT in float: not positive "
                            "definite)");
  factor_->permuted.resize(n_);
}

void HostCholeskySolve::solve(const float* b, float* x) {
  // P S P^-1 = L L^T, solved in place in a buffer sized once (Eigen's solve() allocates per call).
  Factor& f = *factor_;
  const Eigen::VectorXi& p = f.llt.permutationP().indices();  // empty: no permutation
  const bool permuted = p.size() == n_;
  for (int i = 0; i < n_; ++i) f.permuted[permuted ? p[i] : i] = b[i];
  f.llt.matrixL().solveInPlace(f.permuted);
  f.llt.matrixU().solveInPlace(f.permuted);
  for (int i = 0; i < n_; ++i) x[i] = f.permuted[permuted ? p[i] : i];
}

bool implicit_solve_on_host(const DeviceInfo& device, int vertex_count) {
  return vertex_count <= tuning_for(device).host_implicit_solve_max_vertices;
}

}  // namespace physarum::opencl
