// SharedCholesky (common/shared_cholesky.hpp): matrices of one pattern factored on one analysis
// solve their own systems (checked against Eigen's dense LDLT), and a matrix of another pattern is
// refused rather than factored on the wrong analysis.
#include "common/shared_cholesky.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <stdexcept>

namespace physarum {
namespace {

// The path graph Laplacian on n vertices plus `shift` on the diagonal: positive definite for shift > 0.
Eigen::SparseMatrix<double> path(int n, double shift, double weight) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    double diagonal = shift;
    if (i > 0) t.emplace_back(i, i - 1, -weight), diagonal += weight;
    if (i + 1 < n) t.emplace_back(i, i + 1, -weight), diagonal += weight;
    t.emplace_back(i, i, diagonal);
  }
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

TEST(SharedCholesky, MatricesOfOnePatternSolveTheirOwnSystems) {
  const Eigen::SparseMatrix<double> a = path(50, 0.1, 1.0), b = path(50, 2.0, 0.3);
  SharedCholesky shared(a);
  const int ia = shared.factor(a, "a"), ib = shared.factor(b, "b");
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(50, -1.0, 2.0);
  const Eigen::VectorXd xa = shared.solve(ia, rhs), xb = shared.solve(ib, rhs);
  EXPECT_LT((xa - Eigen::MatrixXd(a).ldlt().solve(rhs)).norm(), 1e-10 * xa.norm());
  EXPECT_LT((xb - Eigen::MatrixXd(b).ldlt().solve(rhs)).norm(), 1e-10 * xb.norm());
  EXPECT_GT((xa - xb).norm(), 1.0);  // really two factorizations
}

TEST(SharedCholesky, RefusesAnotherPatternAndIndefiniteMatrices) {
  SharedCholesky shared(path(10, 0.1, 1.0));
  EXPECT_THROW(shared.factor(path(11, 0.1, 1.0), "bigger"), std::invalid_argument);
  Eigen::SparseMatrix<double> indefinite = path(10, -5.0, 1.0);
  EXPECT_THROW(shared.factor(indefinite, "indefinite"), std::runtime_error);
}

// A given ordering is used as given (the factorization's ordering() is it, up to CHOLMOD's postorder
// of the elimination tree, which a path's reversed order already is) and the solve is still exact;
// a principal submatrix factors in the restricted order.
TEST(SharedCholesky, AGivenOrderingIsUsedAndRestricts) {
  const Eigen::SparseMatrix<double> a = path(40, 0.1, 1.0);
  std::vector<int> reversed(40);
  for (int i = 0; i < 40; ++i) reversed[static_cast<size_t>(i)] = 39 - i;
  SharedCholesky shared(a, &reversed);
  EXPECT_EQ(shared.ordering(), reversed);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(40, -1.0, 2.0);
  const Eigen::VectorXd x = shared.solve(shared.factor(a, "a"), rhs);
  EXPECT_LT((x - Eigen::MatrixXd(a).ldlt().solve(rhs)).norm(), 1e-10 * x.norm());

  // Keep the even rows: they are numbered 0..19 in the submatrix, in reversed order.
  std::vector<int> new_index(40, -1);
  for (int i = 0; i < 40; i += 2) new_index[static_cast<size_t>(i)] = i / 2;
  const std::vector<int> restricted = restricted_ordering(reversed, new_index);
  ASSERT_EQ(restricted.size(), 20u);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(restricted[static_cast<size_t>(k)], 19 - k);

  const std::vector<int> too_short(39, 0);
  EXPECT_THROW(SharedCholesky(a, &too_short), std::invalid_argument);
}

}  // namespace
}  // namespace physarum
