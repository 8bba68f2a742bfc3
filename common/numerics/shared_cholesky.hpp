#pragma once
// Sparse Cholesky factorizations (CHOLMOD, supernodal) of several symmetric positive definite matrices
// with ONE sparsity pattern, sharing one symbolic analysis: the fill-reducing ordering (METIS nested
// dissection) of a million-vertex mesh costs about as much as a numeric factorization, so the heat
// method's three systems pay for it once. Eigen's CholmodDecomposition keeps one analysis per
// object, hence this thin wrapper over CHOLMOD's own calls. CHOLMOD analyses and factors; the
// triangular solves are ours (common/numerics/supernodal_solve.hpp), on both cores for large factors.
#include "common/numerics/supernodal_solve.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace physarum {

class SharedCholesky {
 public:
  // Analyses the pattern of `pattern` (compressed, column major, both triangles stored; factor() reads
  // the upper one). Every matrix factored later must have exactly this pattern (explicit zeros count).
  // With `ordering` (a permutation of the rows: ordering[k] is the k-th row eliminated), METIS is
  // skipped and that ordering is used: the symbolic analysis then costs a small fraction of it.
  // Factors storing at least `min_parallel_entries` entries are solved on several threads.
  explicit SharedCholesky(const Eigen::SparseMatrix<double>& pattern, const std::vector<int>* ordering = nullptr,
                          std::size_t min_parallel_entries = kMinParallelSolveEntries);
  ~SharedCholesky();
  SharedCholesky(const SharedCholesky&) = delete;
  SharedCholesky& operator=(const SharedCholesky&) = delete;

  // Factors `matrix` and returns its index for solve(). std::invalid_argument when the pattern
  // differs; std::runtime_error naming `what` when it is not positive definite.
  int factor(const Eigen::SparseMatrix<double>& matrix, const char* what);
  // Ends every numeric factorization (their indices become invalid), keeping the analysis and the
  // factors' memory for the next factor() calls: an iteration that factors a new matrix of the same
  // pattern each time (Newton's method) allocates one factor once. The memory goes with the object.
  void release_factors();
  // x with matrix(index) x = b: forward and backward substitution over the supernodal factor, by
  // subtrees of its elimination tree on several threads when it is large (common/numerics/supernodal_solve.hpp).
  // The same b gives the same bits every time, whatever the machine's thread count. Thread-safe.
  Eigen::VectorXd solve(int index, const Eigen::VectorXd& b) const;
  // The same with CHOLMOD's own (serial) cholmod_solve: the reference for tests and benchmarks.
  // Not thread-safe (CHOLMOD's workspace is shared).
  Eigen::VectorXd cholmod_reference_solve(int index, const Eigen::VectorXd& b) const;
  // How the solve of factor `index` is split (tests).
  const SupernodalSolve& supernodal_solve(int index) const;
  // The elimination order the analysis chose (METIS, postordered): reusable for this pattern and,
  // through restricted_ordering, for its principal submatrices.
  std::vector<int> ordering() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// `ordering` (a permutation of 0..n-1) restricted to the rows kept in a principal submatrix:
// new_index[v] is row v's index in the submatrix, or < 0 where v is dropped. The kept rows keep
// their relative order, which for a nested-dissection order is again one (a separator minus some
// vertices still separates).
std::vector<int> restricted_ordering(const std::vector<int>& ordering, const std::vector<int>& new_index);

// One of a SharedCholesky's factorizations, as something that solves.
struct CholeskyFactor {
  const SharedCholesky* shared = nullptr;
  int index = -1;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const { return shared->solve(index, b); }
};

}  // namespace physarum
