#pragma once
// Sparse Cholesky factorizations (CHOLMOD, supernodal) of several symmetric positive definite matrices
// with ONE sparsity pattern, sharing one symbolic analysis: the fill-reducing ordering (METIS nested
// dissection) of a million-vertex mesh costs about as much as a numeric factorization, so the heat
// method's three systems pay for it once. Eigen's CholmodDecomposition keeps one analysis per
// object, hence this thin wrapper over CHOLMOD's own calls.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>

namespace physarum {

class SharedCholesky {
 public:
  // Analyses the pattern of `pattern` (compressed, column major, both triangles stored; only the lower
  // one is read). Every matrix factored later must have exactly this pattern (explicit zeros count).
  explicit SharedCholesky(const Eigen::SparseMatrix<double>& pattern);
  ~SharedCholesky();
  SharedCholesky(const SharedCholesky&) = delete;
  SharedCholesky& operator=(const SharedCholesky&) = delete;

  // Factors `matrix` and returns its index for solve(). std::invalid_argument when the pattern
  // differs; std::runtime_error naming `what` when it is not positive definite.
  int factor(const Eigen::SparseMatrix<double>& matrix, const char* what);
  // x with matrix(index) x = b. Not thread-safe (CHOLMOD's workspace is shared).
  Eigen::VectorXd solve(int index, const Eigen::VectorXd& b) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// One of a SharedCholesky's factorizations, as something that solves.
struct CholeskyFactor {
  const SharedCholesky* shared = nullptr;
  int index = -1;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const { return shared->solve(index, b); }
};

}  // namespace physarum
