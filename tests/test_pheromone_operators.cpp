// The pheromone operators of common/model/pheromone_operators.hpp against the same operators built as
// dense Eigen matrices from Eq. 6 and Eq. 7 on small meshes: the forward Euler sub-step matrix
// entry by entry, and the symmetrised backward Euler system by its structure (S symmetric positive
// definite, identity rows where nothing diffuses) and by its solution, which must be Eq. 7's.
#include "common/model/pheromone_operators.hpp"
#include "pheromone_test_meshes.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <random>

namespace physarum {
namespace {

using testing::make_domain;
using testing::make_icosphere;
using testing::make_square_grid;

Eigen::MatrixXd dense(const CsrMatrix& m) { return Eigen::MatrixXd(m.to_eigen()); }

Eigen::MatrixXd diagonal(const IntrinsicVertexData<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())).asDiagonal();
}

// Rates that vary over the mesh; every third vertex does not diffuse when `some_zero`.
void varying_rates(const InputMesh& mesh, bool some_zero, IntrinsicVertexData<double>& diffuse, IntrinsicVertexData<double>& decay) {
  const size_t n = mesh.positions.size();
  diffuse.assign(n, 0.0);
  decay.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    diffuse[i] = some_zero && i % 3 == 0 ? 0.0 : 0.001 + 0.01 * std::abs(mesh.positions[i].x());
    decay[i] = 0.2 + std::abs(mesh.positions[i].y());
  }
}

TEST(PheromoneOperators, ForwardSubStepMatrixIsEquationSixOverMass) {
  const InputMesh mesh = make_square_grid(5, true, 0.2);
  const SurfaceDomain domain = make_domain(mesh);
  IntrinsicVertexData<double> diffuse, decay;
  varying_rates(mesh, true, diffuse, decay);
  IntrinsicVertexData<double> diffuse_over_mass(diffuse.size());
  for (size_t i = 0; i < diffuse.size(); ++i) diffuse_over_mass[i] = diffuse[i] / domain.vertex_mass[i];
  const double h = 0.01;
  const CsrMatrix F = forward_substep_matrix(domain.laplacian, diffuse_over_mass, decay, h);
  const int n = domain.vertex_count;
  ASSERT_EQ(F.rows, n);
  ASSERT_EQ(F.cols, n);
  const Eigen::MatrixXd L = dense(domain.laplacian);
  const Eigen::MatrixXd expected =
      Eigen::MatrixXd::Identity(n, n) - h * (diagonal(diffuse_over_mass) * L + diagonal(decay));
  EXPECT_LT((dense(F) - expected).cwiseAbs().maxCoeff(), 1e-15);
  // L's sparsity, each row with its diagonal entry.
  for (int i = 0; i < n; ++i) {
    bool has_diagonal = false;
    for (int k = F.row_start[i]; k < F.row_start[i + 1]; ++k) has_diagonal |= F.column[k] == i;
    EXPECT_TRUE(has_diagonal) << "row " << i;
  }
}

// S u' = B u must be [M + dt (R_dif L + R_dec M)] u' = M u, for uniform, varying and partly zero
// diffusion, and none at all.
TEST(PheromoneOperators, BackwardEulerSystemIsSymmetricAndSolvesEquationSeven) {
  const InputMesh mesh = make_icosphere(1);
  const SurfaceDomain domain = make_domain(mesh);
  const int n = domain.vertex_count;
  const Eigen::MatrixXd L = dense(domain.laplacian);
  const Eigen::MatrixXd M = diagonal(domain.vertex_mass);
  const double dt = 0.3;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Eigen::VectorXd u(n);
  for (int i = 0; i < n; ++i) u[i] = uniform(rng);
  for (int variant = 0; variant < 4; ++variant) {
    IntrinsicVertexData<double> diffuse, decay;
    varying_rates(mesh, variant == 1, diffuse, decay);
    if (variant == 2) diffuse.assign(diffuse.size(), 0.02);
    if (variant == 3) diffuse.assign(diffuse.size(), 0.0);
    SCOPED_TRACE("variant " + std::to_string(variant));
    const BackwardEulerSystem system = backward_euler_system(domain.laplacian, domain.vertex_mass, diffuse, decay, dt);
    EXPECT_EQ(system.diagonal_only, variant == 3);
    const Eigen::MatrixXd S = dense(system.system), B = dense(system.rhs);
    ASSERT_EQ(S.rows(), n);
    ASSERT_EQ(B.rows(), n);
    EXPECT_LT((S - S.transpose()).cwiseAbs().maxCoeff(), 1e-15 * S.cwiseAbs().maxCoeff());
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(S).info(), Eigen::Success) << "S is positive definite";
    for (int i = 0; i < n; ++i) {
      EXPECT_DOUBLE_EQ(system.inverse_diagonal[static_cast<size_t>(i)], 1.0 / S(i, i)) << "vertex " << i;
      if (diffuse[static_cast<size_t>(i)] == 0.0) {
        EXPECT_EQ(S.row(i).cwiseAbs().sum(), 1.0) << "an identity row at vertex " << i;
        EXPECT_EQ(S(i, i), 1.0);
      }
    }
    const Eigen::VectorXd solved = S.llt().solve(B * u);
    const Eigen::VectorXd expected =
        (M + dt * (diagonal(diffuse) * L + diagonal(decay) * M)).partialPivLu().solve(M * u);
    EXPECT_LT((solved - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  }
}

}  // namespace
}  // namespace physarum
