// The reference pheromone PDE (paper Eq. 1, 6, 7): conservation, exact decay factors, the stability
// bound and its sub-steps, the backward-Euler recursion and an analytic diffusion eigenmode.
#include "mass_integral.hpp"
#include "pheromone_rates.hpp"
#include "pheromone_test_meshes.hpp"
#include "random_vertex_values.hpp"
#include "reference_field.hpp"

#include "common/base/errors.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using testing::make_domain;
using testing::make_icosphere;
using testing::make_square_grid;
using testing::mass_integral;
using testing::random_values;
using testing::uniform_rates;

// Diffusion alone (r_dec = 0) only moves pheromone: 1^T L = 0 makes sum_i m_i u_i invariant.
TEST(Pheromone, DiffusionAloneConservesTotalAmount) {
  // A square grid (boundary = Neumann) has vertex masses that differ (corners, edges, interior),
  // so a scheme that forgot M^-1 would not conserve the mass-weighted total.
  const SurfaceDomain domain = make_domain(make_square_grid(16));
  for (Integrator integrator : {Integrator::Forward, Integrator::Backward}) {
    testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, 0.01, 0.0), integrator, 0.01);
    field.set_concentration(random_values(domain.vertex_count, 7, 0.0, 1.0));
    const double before = mass_integral(domain, field.concentration());
    for (int s = 0; s < 300; ++s) field.step();
    EXPECT_NEAR(mass_integral(domain, field.concentration()) / before, 1.0, 1e-6);
    EXPECT_NEAR(field.total_amount() / before, 1.0, 1e-6);
    // ... and it really diffused: the field is much smoother than the random start.
    const auto [lo, hi] = std::minmax_element(field.concentration().begin(), field.concentration().end());
    EXPECT_LT(*hi - *lo, 0.5);
  }
}

// Decay alone (r_dif = 0): Eq. 6 gives u' = (1 - r dt) u, Eq. 7 gives u' = u / (1 + r dt), vertex by vertex.
TEST(Pheromone, DecayAloneScalesEveryVertexExactly) {
  const SurfaceDomain domain = make_domain(make_icosphere(2));
  const double r = 0.7, dt = 0.05;
  const IntrinsicVertexData<double> start = random_values(domain.vertex_count, 3, 0.0, 1.0);
  for (Integrator integrator : {Integrator::Forward, Integrator::Backward}) {
    testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, 0.0, r), integrator, dt);
    EXPECT_EQ(field.sub_steps(), 1);
    field.set_concentration(start);
    field.step();
    const double factor = integrator == Integrator::Forward ? 1.0 - r * dt : 1.0 / (1.0 + r * dt);
    for (int i = 0; i < domain.vertex_count; ++i)
      ASSERT_NEAR(field.concentration()[i], factor * start[i], 1e-12 * start[i]) << "vertex " << i;
  }
}

TEST(Pheromone, DecayAloneApproachesExponential) {
  const SurfaceDomain domain = make_domain(make_icosphere(1));
  const double r = 1.3, dt = 1e-4, t_end = 1.0;
  for (Integrator integrator : {Integrator::Forward, Integrator::Backward}) {
    testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, 0.0, r), integrator, dt);
    field.fill(2.0);
    const int steps = static_cast<int>(std::lround(t_end / dt));
    for (int s = 0; s < steps; ++s) field.step();
    // Euler's global error is ~ r^2 t dt / 2 = 8.5e-5 relative here.
    for (double u : field.concentration()) ASSERT_NEAR(u / (2.0 * std::exp(-r * t_end)), 1.0, 2e-4);
  }
}

// A constant field is in the kernel of L, so even with diffusion on, Eq. 7 reduces to the scalar
// recursion c_{n+1} = c_n / (1 + r dt) (and Eq. 6 to c_{n+1} = (1 - r dt) c_n).
TEST(Pheromone, ConstantFieldFollowsScalarRecursion) {
  const SurfaceDomain domain = make_domain(make_icosphere(2));
  const double r = 0.4, dt = 0.1, c0 = 3.0;
  for (Integrator integrator : {Integrator::Backward, Integrator::Forward}) {
    testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, 0.05, r), integrator, dt);
    field.fill(c0);
    const int steps = 25;
    for (int s = 0; s < steps; ++s) field.step();
    const double expected = integrator == Integrator::Backward ? c0 / std::pow(1.0 + r * dt, steps)
                                                                    : c0 * std::pow(1.0 - r * dt / field.sub_steps(), steps * field.sub_steps());
    for (double u : field.concentration()) ASSERT_NEAR(u, expected, 1e-10 * expected);
  }
}

// On the unit sphere z is an eigenfunction of the Laplace-Beltrami operator with eigenvalue
// l(l+1) = 2, so the PDE gives u(t) = z exp(-(2 r_dif + r_dec) t). On a 642-vertex icosphere the
// amplitude after t = 2 s lands within 2.5e-4 of that (space and time discretisation together);
// 3e-3 allows that with margin, while a diffusion term only 3 % off would already miss by 1.2e-2.
TEST(Pheromone, SphericalHarmonicDecaysAtAnalyticRate) {
  const InputMesh sphere = make_icosphere(3);
  const SurfaceDomain domain = make_domain(sphere);
  const double r_dif = 0.1, r_dec = 0.3, t_end = 2.0;
  IntrinsicVertexData<double> z(static_cast<size_t>(domain.vertex_count));
  for (int i = 0; i < domain.vertex_count; ++i) z[i] = sphere.positions[i].z();
  auto m_dot = [&](const IntrinsicVertexData<double>& a, const IntrinsicVertexData<double>& b) {
    double s = 0;
    for (int i = 0; i < domain.vertex_count; ++i) s += domain.vertex_mass[i] * a[i] * b[i];
    return s;
  };
  const double expected = std::exp(-(2.0 * r_dif + r_dec) * t_end);
  for (auto [integrator, dt] : {std::pair{Integrator::Forward, 1e-3}, std::pair{Integrator::Backward, 1e-3}}) {
    testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, r_dif, r_dec), integrator, dt);
    field.set_concentration(z);
    const int steps = static_cast<int>(std::lround(t_end / dt));
    for (int s = 0; s < steps; ++s) field.step();
    const IntrinsicVertexData<double>& u = field.concentration();
    const double amplitude = m_dot(u, z) / m_dot(z, z);
    EXPECT_NEAR(amplitude / expected, 1.0, 3e-3) << (integrator == Integrator::Forward ? "forward" : "backward");
    // The shape is preserved: what is left after removing the z component is tiny.
    IntrinsicVertexData<double> rest(u.size());
    for (size_t i = 0; i < u.size(); ++i) rest[i] = u[i] - amplitude * z[i];
    EXPECT_LT(std::sqrt(m_dot(rest, rest) / m_dot(z, z)), 1e-3 * expected);
  }
}

// The sub-step bound: it must be stable (dt * lambda_max <= 2, lambda_max of M^-1 R_dif L + R_dec
// computed here independently by power iteration) and not needlessly small.
TEST(Pheromone, StableTimeStepRespectsTrueSpectralRadius) {
  const SurfaceDomain domain = make_domain(make_icosphere(3));
  const double r_dif = 0.02, r_dec = 0.5;
  testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, r_dif, r_dec), Integrator::Forward, 1.0);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> L = domain.laplacian.to_eigen();
  Eigen::VectorXd inv_m(domain.vertex_count);
  for (int i = 0; i < domain.vertex_count; ++i) inv_m[i] = 1.0 / domain.vertex_mass[i];
  Eigen::VectorXd x = Eigen::VectorXd::Random(domain.vertex_count);
  double lambda = 0;
  for (int it = 0; it < 3000; ++it) {
    Eigen::VectorXd y = r_dif * inv_m.cwiseProduct(L * x) + r_dec * x;
    lambda = y.norm() / x.norm();
    x = y / y.norm();
  }
  const double h = field.stable_time_step();
  EXPECT_LE(h * lambda, 2.0);
  EXPECT_GE(h * lambda, 0.25 * 2.0) << "bound far more pessimistic than the true spectral radius";
}

// Above the bound, step() splits into sub-steps and the field stays non-negative and bounded;
// without them, the same single Euler step would go negative (checked here by hand).
TEST(Pheromone, SubStepsAboveLimitKeepFieldNonNegative) {
  const SurfaceDomain domain = make_domain(make_icosphere(3));
  const double r_dif = 0.05, r_dec = 0.2;
  const VertexParameters p = uniform_rates(domain.vertex_count, r_dif, r_dec);
  const double limit = testing::ReferenceField(domain, p, Integrator::Forward, 1.0).stable_time_step();
  const double dt = 10.0 * limit;
  testing::ReferenceField field(domain, p, Integrator::Forward, dt);
  EXPECT_GE(field.sub_steps(), 10);
  EXPECT_LE(field.sub_steps(), 11);

  IntrinsicVertexData<double> spike(static_cast<size_t>(domain.vertex_count), 0.0);
  spike[5] = 1.0;
  // One unsplit Euler step at dt: u'_5 = 1 - dt (r_dif L_55 / m_5 + r_dec) < 0.
  double L55 = 0;
  for (int k = domain.laplacian.row_start[5]; k < domain.laplacian.row_start[6]; ++k)
    if (domain.laplacian.column[k] == 5) L55 = domain.laplacian.value[k];
  ASSERT_LT(1.0 - dt * (r_dif * L55 / domain.vertex_mass[5] + r_dec), 0.0) << "test premise: unsplit step overshoots";

  field.set_concentration(spike);
  for (int s = 0; s < 50; ++s) {
    field.step();
    for (double u : field.concentration()) {
      ASSERT_GE(u, 0.0);
      ASSERT_LE(u, 1.0);
    }
  }
}

// Below the bound, exactly one plain Euler step is taken: compare with Eq. 6 evaluated by hand.
TEST(Pheromone, NoSubStepsBelowLimit) {
  const SurfaceDomain domain = make_domain(make_square_grid(8));
  const VertexParameters p = uniform_rates(domain.vertex_count, 0.01, 0.3);
  const double limit = testing::ReferenceField(domain, p, Integrator::Forward, 1.0).stable_time_step();
  const double dt = 0.95 * limit;
  testing::ReferenceField field(domain, p, Integrator::Forward, dt);
  EXPECT_EQ(field.sub_steps(), 1);
  const IntrinsicVertexData<double> u0 = random_values(domain.vertex_count, 11, 0.0, 1.0);
  field.set_concentration(u0);
  field.step();
  const Eigen::SparseMatrix<double, Eigen::RowMajor> L = domain.laplacian.to_eigen();
  const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(u0.data(), domain.vertex_count);
  const Eigen::VectorXd Lu = L * u;
  for (int i = 0; i < domain.vertex_count; ++i) {
    const double expected = u[i] - dt * (0.01 * Lu[i] / domain.vertex_mass[i] + 0.3 * u[i]);
    ASSERT_NEAR(field.concentration()[i], expected, 1e-13);
  }
}

// Spatially varying rates (Sec. 3.3): backward Euler takes the non-symmetric LU path; its result
// must solve Eq. 7, checked against a dense solve assembled here; forward matches Eq. 6 by hand.
TEST(Pheromone, VaryingRatesSolveEquationsSixAndSeven) {
  const InputMesh grid = make_square_grid(6);
  const SurfaceDomain domain = make_domain(grid);
  const int n = domain.vertex_count;
  VertexParameters p = uniform_rates(n, 0.0, 0.0);
  for (int i = 0; i < n; ++i) {
    p[Param::diffuse_rate][i] = 0.001 + 0.01 * grid.positions[i].x();
    p[Param::decay_rate][i] = 0.2 + grid.positions[i].y();
  }
  const double dt = 0.5;
  const IntrinsicVertexData<double> u0 = random_values(n, 5, 0.0, 1.0);
  const Eigen::MatrixXd L = Eigen::MatrixXd(domain.laplacian.to_eigen());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), Rdif = M, Rdec = M;
  for (int i = 0; i < n; ++i) {
    M(i, i) = domain.vertex_mass[i];
    Rdif(i, i) = p[Param::diffuse_rate][i];
    Rdec(i, i) = p[Param::decay_rate][i];
  }
  const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(u0.data(), n);

  testing::ReferenceField backward(domain, p, Integrator::Backward, dt);
  backward.set_concentration(u0);
  backward.step();
  const Eigen::VectorXd expected_backward = (M + dt * (Rdif * L + Rdec * M)).partialPivLu().solve(M * u);
  for (int i = 0; i < n; ++i) ASSERT_NEAR(backward.concentration()[i], expected_backward[i], 1e-12);

  testing::ReferenceField forward(domain, p, Integrator::Forward, 0.01);
  ASSERT_EQ(forward.sub_steps(), 1);
  forward.set_concentration(u0);
  forward.step();
  const Eigen::VectorXd expected_forward = M.inverse() * ((M - 0.01 * (Rdif * L + Rdec * M)) * u);
  for (int i = 0; i < n; ++i) ASSERT_NEAR(forward.concentration()[i], expected_forward[i], 1e-12);
}

// A deposit is an amount: it raises the mass-weighted total by exactly that amount.
TEST(Pheromone, DepositsAddAmountOverVertexMass) {
  const SurfaceDomain domain = make_domain(make_icosphere(2));
  testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, 0.01, 1.0), Integrator::Forward, 0.01);
  field.add_deposit(17, 0.25);
  EXPECT_DOUBLE_EQ(field.concentration()[17], 0.25 / domain.vertex_mass[17]);
  EXPECT_NEAR(field.total_amount(), 0.25, 1e-15);
  IntrinsicVertexData<double> amounts(static_cast<size_t>(domain.vertex_count), 0.0);
  amounts[3] = 1.0;
  amounts[17] = 0.5;
  field.add_deposits(amounts);
  EXPECT_NEAR(field.total_amount(), 1.75, 1e-14);
  EXPECT_DOUBLE_EQ(field.concentration()[17], 0.75 / domain.vertex_mass[17]);
  EXPECT_THROW(field.add_deposits(IntrinsicVertexData<double>(3, 0.0)), InputError);
}

// Deposits spread uniformly at N r_dep per second with backward Euler settle at exactly U (Eq. 5,
// no turnover): the fixed point of u = (u + d) / (1 + r dt) is d / (r dt) = N r_dep / (r A).
TEST(Pheromone, UniformDepositsSettleAtAnalyticSteadyState) {
  const SurfaceDomain domain = make_domain(make_icosphere(2));
  const double agents = 200, deposit_rate = 0.5, r_dec = 2.0, dt = 0.05;
  testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, 0.001, r_dec), Integrator::Backward, dt);
  IntrinsicVertexData<double> amounts(static_cast<size_t>(domain.vertex_count));
  double area = 0;
  for (double m : domain.vertex_mass) area += m;
  for (int i = 0; i < domain.vertex_count; ++i) amounts[i] = agents * deposit_rate * dt * domain.vertex_mass[i] / area;
  for (int s = 0; s < 2000; ++s) {
    field.add_deposits(amounts);
    field.step();
  }
  const double U = agents * deposit_rate / (r_dec * area);
  for (double u : field.concentration()) ASSERT_NEAR(u / U, 1.0, 1e-9);
}

TEST(Pheromone, RejectsMismatchedSizesAndBadTimeStep) {
  const SurfaceDomain domain = make_domain(make_icosphere(1));
  EXPECT_THROW(
      testing::ReferenceField(domain, uniform_rates(domain.vertex_count - 1, 0.1, 0.1), Integrator::Forward, 0.1),
      InputError);
  EXPECT_THROW(testing::ReferenceField(domain, uniform_rates(domain.vertex_count, 0.1, 0.1), Integrator::Forward, 0.0),
               InputError);
  testing::ReferenceField field(domain, uniform_rates(domain.vertex_count, 0.1, 0.1), Integrator::Forward, 0.1);
  EXPECT_THROW(field.set_concentration(IntrinsicVertexData<double>(2, 0.0)), InputError);
}

}  // namespace
}  // namespace physarum
