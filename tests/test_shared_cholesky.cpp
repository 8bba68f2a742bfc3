// SharedCholesky (common/numerics/shared_cholesky.hpp): matrices of one pattern factored on one analysis
// solve their own systems (checked against Eigen's dense LDLT), and a matrix of another pattern is
// refused rather than factored on the wrong analysis. Our supernodal solve (common/numerics/supernodal_solve.hpp),
// serial and split into subtrees, matches CHOLMOD's own cholmod_solve and repeats itself bit for bit.
#include "common/numerics/shared_cholesky.hpp"
#include "tests/pheromone_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <cmath>
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

// Released and refused factors are refactored in place: what they held before (another matrix, or
// a failed factorization's partial columns) leaves no trace in the next factorization's solve.
TEST(SharedCholesky, AReusedFactorSolvesLikeAFreshOne) {
  const Eigen::SparseMatrix<double> a = path(60, 0.1, 1.0), b = path(60, 2.0, 0.3);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(60, -1.0, 2.0);
  SharedCholesky fresh(a), reused(a);
  const Eigen::VectorXd expected = fresh.solve(fresh.factor(b, "b"), rhs);
  reused.factor(a, "a");
  reused.release_factors();
  EXPECT_THROW(reused.factor(path(60, -5.0, 1.0), "indefinite"), std::runtime_error);
  const Eigen::VectorXd after_refusal = reused.solve(reused.factor(b, "b"), rhs);
  EXPECT_EQ(after_refusal, expected);  // the same arithmetic: bit for bit
  reused.release_factors();
  EXPECT_EQ(reused.solve(reused.factor(b, "b"), rhs), expected);
  EXPECT_LT((expected - Eigen::MatrixXd(b).ldlt().solve(rhs)).norm(), 1e-10 * expected.norm());
}

// factor() reads the upper triangle: a matrix whose lower triangle disagrees is solved as the
// symmetric matrix of its upper one.
TEST(SharedCholesky, FactorReadsTheUpperTriangle) {
  const Eigen::SparseMatrix<double> a = path(30, 0.5, 1.0);
  Eigen::SparseMatrix<double> lower_spoiled = a;
  for (int k = 0; k < lower_spoiled.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower_spoiled, k); it; ++it)
      if (it.row() > it.col()) it.valueRef() = -0.25;
  SharedCholesky shared(a);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(30, -1.0, 2.0);
  const Eigen::VectorXd x = shared.solve(shared.factor(lower_spoiled, "spoiled"), rhs);
  EXPECT_LT((x - Eigen::MatrixXd(a).ldlt().solve(rhs)).norm(), 1e-10 * x.norm());
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

// M + tL of a unit icosphere (level 4: 2562 vertices), the heat method's matrix.
Eigen::SparseMatrix<double> sphere_heat_matrix(int level, double t) {
  const SurfaceDomain domain = testing::make_domain(testing::make_icosphere(level));
  Eigen::SparseMatrix<double> m = t * Eigen::SparseMatrix<double>(domain.laplacian.to_eigen());
  for (int v = 0; v < domain.vertex_count; ++v) m.coeffRef(v, v) += domain.vertex_mass[static_cast<size_t>(v)];
  m.makeCompressed();
  return m;
}

// A right-hand side with no structure the solve could be lucky with.
Eigen::VectorXd wiggly(Eigen::Index n) {
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = std::sin(0.7 * static_cast<double>(i)) + 0.3 * std::cos(0.05 * static_cast<double>(i * i));
  return b;
}

double relative_difference(const Eigen::VectorXd& x, const Eigen::VectorXd& reference) {
  return (x - reference).norm() / reference.norm();
}

// Every solve of `a` (factored on `shared`) agrees with CHOLMOD's and with Eigen's simplicial LDL',
// and gives the same bits when repeated.
void expect_solves_like_cholmod(const SharedCholesky& shared, int index, const Eigen::SparseMatrix<double>& a) {
  const Eigen::VectorXd b = wiggly(a.rows());
  const Eigen::VectorXd x = shared.solve(index, b);
  EXPECT_LT(relative_difference(x, shared.cholmod_reference_solve(index, b)), 1e-12);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
  EXPECT_LT(relative_difference(x, ldlt.solve(b)), 1e-11);
  EXPECT_LT((a * x - b).norm(), 1e-11 * b.norm() * a.norm());
  for (int repeat = 0; repeat < 50; ++repeat) {
    const Eigen::VectorXd again = shared.solve(index, b);
    ASSERT_EQ(again.size(), x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) ASSERT_EQ(again[i], x[i]) << "repeat " << repeat << ", row " << i;
  }
}

TEST(SupernodalSolve, MeshMatrixSplitIntoSubtreesSolvesLikeCholmod) {
  const Eigen::SparseMatrix<double> a = sphere_heat_matrix(4, 0.01);
  SharedCholesky shared(a, nullptr, 0);  // parallel at any size
  const int index = shared.factor(a, "M + tL");
  const SupernodalSolve& plan = shared.supernodal_solve(index);
  EXPECT_EQ(plan.bins(), kSolveBins);
  expect_solves_like_cholmod(shared, index, a);

  // The same factor at the default threshold: serial, and the same answer to rounding.
  SharedCholesky serial(a);
  const int serial_index = serial.factor(a, "M + tL");
  EXPECT_EQ(serial.supernodal_solve(serial_index).bins(), 0);
  const Eigen::VectorXd b = wiggly(a.rows());
  EXPECT_LT(relative_difference(shared.solve(index, b), serial.solve(serial_index, b)), 1e-13);
  expect_solves_like_cholmod(serial, serial_index, a);
}

TEST(SupernodalSolve, TinySystems) {
  for (const std::size_t threshold : {std::size_t{0}, kMinParallelSolveEntries}) {
    Eigen::SparseMatrix<double> one(1, 1);
    one.insert(0, 0) = 4.0;
    one.makeCompressed();
    SharedCholesky shared_one(one, nullptr, threshold);
    const Eigen::VectorXd x = shared_one.solve(shared_one.factor(one, "one"), Eigen::VectorXd::Constant(1, 2.0));
    ASSERT_EQ(x.size(), 1);
    EXPECT_DOUBLE_EQ(x[0], 0.5);

    const Eigen::SparseMatrix<double> a = path(3, 0.5, 1.0);
    SharedCholesky shared(a, nullptr, threshold);
    const int index = shared.factor(a, "path");
    expect_solves_like_cholmod(shared, index, a);
    EXPECT_THROW(shared.solve(index, Eigen::VectorXd::Ones(4)), std::invalid_argument);
  }
}

// Several connected components: the elimination tree is a forest, each tree a root of its own,
// of very different weights (so the split takes some apart and leaves others whole).
TEST(SupernodalSolve, SeveralComponentsSolveLikeCholmod) {
  const Eigen::SparseMatrix<double> sphere = sphere_heat_matrix(3, 0.02), strip = path(300, 0.05, 1.0);
  const Eigen::Index n = 2 * sphere.rows() + strip.rows() + 7;
  std::vector<Eigen::Triplet<double>> t;
  auto place = [&](const Eigen::SparseMatrix<double>& block, Eigen::Index offset) {
    for (int col = 0; col < block.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(block, col); it; ++it)
        t.emplace_back(static_cast<int>(offset + it.row()), static_cast<int>(offset + col), it.value());
  };
  place(sphere, 0);
  place(strip, sphere.rows());
  place(sphere * 2.0, sphere.rows() + strip.rows());
  for (Eigen::Index i = n - 7; i < n; ++i) t.emplace_back(static_cast<int>(i), static_cast<int>(i), 1.0 + static_cast<double>(i % 3));  // lone vertices
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  SharedCholesky shared(a, nullptr, 0);
  const int index = shared.factor(a, "forest");
  EXPECT_EQ(shared.supernodal_solve(index).bins(), kSolveBins);
  expect_solves_like_cholmod(shared, index, a);
}

// The 7-point Laplacian of an n^3 grid plus `shift`: its nested-dissection separators are whole
// planes (n^2 rows), dense enough at n = 24 that the top supernodes are cut into blocks.
Eigen::SparseMatrix<double> cube_grid(int n, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  auto index = [n](int i, int j, int k) { return (k * n + j) * n + i; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int v = index(i, j, k);
        double diagonal = shift;
        const int neighbours[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
        for (const auto& w : neighbours)
          if (w[0] >= 0 && w[0] < n && w[1] >= 0 && w[1] < n && w[2] >= 0 && w[2] < n) {
            t.emplace_back(v, index(w[0], w[1], w[2]), -1.0);
            diagonal += 1.0;
          }
        t.emplace_back(v, v, diagonal);
      }
  Eigen::SparseMatrix<double> m(n * n * n, n * n * n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

TEST(SupernodalSolve, LargeSeparatorsCutIntoBlocksSolveLikeCholmod) {
  const Eigen::SparseMatrix<double> a = cube_grid(24, 0.01);
  SharedCholesky shared(a, nullptr, 0);
  const int index = shared.factor(a, "cube");
  const SupernodalSolve& plan = shared.supernodal_solve(index);
  EXPECT_EQ(plan.bins(), kSolveBins);
  EXPECT_GT(plan.top_tasks(), 2 * plan.top_supernodes());  // some top supernodes are in blocks
  expect_solves_like_cholmod(shared, index, a);
}

// The solve in float (the device fields' implicit step, opencl/host_cholesky_solve.hpp) on the
// double factor rounded once: serial and split into subtrees (with the top's large supernodes in
// blocks, on the cube), it agrees with the double solve to float's precision times the condition
// number (M + tL at t = 0.01 on the sphere and the cube: below 100), and repeats itself bit for bit.
TEST(SupernodalSolve, FloatFactorSolvesLikeTheDoubleOne) {
  for (const bool cube : {false, true}) {
    const Eigen::SparseMatrix<double> a = cube ? cube_grid(24, 0.01) : sphere_heat_matrix(4, 0.01);
    SharedCholesky shared(a, nullptr, 0);
    const int index = shared.factor(a, "M + tL");
    const SupernodalFactorView& d = shared.supernodal_solve(index).factor();
    const std::vector<float> values(d.x, d.x + d.px[d.supernodes]);
    BasicSupernodalFactorView<float> f;
    f.n = d.n;
    f.supernodes = d.supernodes;
    f.super = d.super;
    f.pi = d.pi;
    f.px = d.px;
    f.s = d.s;
    f.x = values.data();
    f.perm = d.perm;
    const BasicSupernodalSolve<float> split(f, 0), serial(f, std::size_t{1} << 40);
    ASSERT_EQ(split.bins(), kSolveBins);
    ASSERT_EQ(serial.bins(), 0);
    if (cube) {
      EXPECT_GT(split.top_tasks(), 2 * split.top_supernodes());
    }
    const Eigen::VectorXd b = wiggly(a.rows());
    const Eigen::VectorXd x = shared.solve(index, b);
    const Eigen::VectorXf bf = b.cast<float>();
    for (const BasicSupernodalSolve<float>* plan : {&split, &serial}) {
      const Eigen::VectorXf xf = plan->solve(bf);
      EXPECT_LT(relative_difference(xf.cast<double>(), x), 100 * 6e-8) << (cube ? "cube" : "sphere")
                                                                        << (plan == &split ? ", split" : ", serial");
      const Eigen::VectorXf again = plan->solve(bf);
      for (Eigen::Index i = 0; i < xf.size(); ++i) ASSERT_EQ(again[i], xf[i]) << "row " << i;
    }
  }
}

}  // namespace
}  // namespace physarum
