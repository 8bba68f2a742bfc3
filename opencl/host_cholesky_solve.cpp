#include "opencl/host_cholesky_solve.hpp"

#include "common/errors.hpp"

#include <Eigen/SparseCholesky>

namespace physarum::opencl {

struct HostCholeskySolve::Factor {
  Eigen::SimplicialLLT<Eigen::SparseMatrix<float>> llt;
  Eigen::VectorXf permuted;  // P b, then the solution in the factor's order
};

HostCholeskySolve::~HostCholeskySolve() = default;

HostCholeskySolve::HostCholeskySolve(const ComputeContext& compute, const CsrMatrix& system)
    : compute_(compute), n_(system.rows), factor_(std::make_unique<Factor>()), host_(static_cast<size_t>(system.rows)) {
  // S is symmetric, so its CSR rows are its CSC columns.
  const Eigen::SparseMatrix<float> s = system.to_eigen().cast<float>();
  factor_->llt.compute(s);
  if (factor_->llt.info() != Eigen::Success)
    throw InputError("opencl pheromone: the backward-Euler system could not be factorised on the host (LLT)");
  factor_->permuted.resize(n_);
  b_ = allocate_written<cl_float>(compute, "backward Euler right-hand side", static_cast<size_t>(n_));
}

void HostCholeskySolve::solve(const DeviceBuffer& x) {
  const size_t bytes = host_.size() * sizeof(float);
  compute_.queue.enqueueReadBuffer(b_.buffer, CL_TRUE, 0, bytes, host_.data());
  // P S P^-1 = L L^T, solved in place in buffers sized once (Eigen's solve() allocates per call).
  Factor& f = *factor_;
  const Eigen::VectorXi& p = f.llt.permutationP().indices();  // empty: no permutation
  const bool permuted = p.size() == n_;
  for (int i = 0; i < n_; ++i) f.permuted[permuted ? p[i] : i] = host_[static_cast<size_t>(i)];
  f.llt.matrixL().solveInPlace(f.permuted);
  f.llt.matrixU().solveInPlace(f.permuted);
  for (int i = 0; i < n_; ++i) host_[static_cast<size_t>(i)] = f.permuted[permuted ? p[i] : i];
  // Blocking: host_ must outlive the copy (a copy within the host's RAM on a CPU device).
  compute_.queue.enqueueWriteBuffer(x.buffer, CL_TRUE, 0, bytes, host_.data());
}

}  // namespace physarum::opencl
