// The reference reaction-diffusion backend (reference/reaction_diffusion.hpp) against answers derived
// here from the continuum equations: uniform steady states, the linear-stability growth rate of a
// spherical harmonic, Turing's instability threshold, the explicit stability limit, Pearson's
// Gray-Scott spreading, and Dirichlet vertices that never move.
#include "reaction_diffusion_scene.hpp"
#include "reference/reaction_diffusion.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;
using testing::load_rd_system;
using testing::vertex_positions;

double max_deviation(const IntrinsicVertexData<double>& u, double value) {
  double d = 0.0;
  for (const double x : u) d = std::max(d, std::abs(x - value));
  return d;
}

// Area-weighted variance.
double variance(const IntrinsicVertexData<double>& u, const IntrinsicVertexData<double>& mass) {
  double area = 0.0, mean = 0.0, var = 0.0;
  for (size_t i = 0; i < u.size(); ++i) area += mass[i], mean += mass[i] * u[i];
  mean /= area;
  for (size_t i = 0; i < u.size(); ++i) var += mass[i] * (u[i] - mean) * (u[i] - mean);
  return var / area;
}

TEST(ReactionDiffusionReference, UniformSteadyStatesStayFixedOver10000Steps) {
  // Gray-Scott's trivial state (1, 0), and Turing's (4, 4) for alpha = 16, beta = 12 (u v = alpha,
  // u v - v = beta), with diffusion that keeps it stable (D_u / D_v = 2, below the critical 4).
  {
    const auto rd = load_rd_system({{"mesh", "shape:square"}, {"time_step", 1.0}, {"model", "gray-scott"}});
    ReferenceReactionDiffusion sim(rd.system);
    sim.run(10000);
    EXPECT_LT(max_deviation(sim.field(0), 1.0), 1e-6);
    EXPECT_LT(max_deviation(sim.field(1), 0.0), 1e-6);
  }
  {
    const auto rd = load_rd_system({{"mesh", "shape:square"},
                                    {"time_step", 1.0},
                                    {"model", "turing"},
                                    {"parameters", {{"alpha", 16.0}, {"beta", 12.0}, {"rho", 0.035}}},
                                    {"morphogens", {{"u", {{"diffusion", 1e-4}, {"initial", 4.0}}},
                                                    {"v", {{"diffusion", 5e-5}, {"initial", 4.0}}}}}});
    ReferenceReactionDiffusion sim(rd.system);
    sim.run(10000);
    EXPECT_LT(max_deviation(sim.field(0), 4.0), 1e-6);
    EXPECT_LT(max_deviation(sim.field(1), 4.0), 1e-6);
  }
}

// The growth rate of a perturbation eps * e * Y_l on the unit sphere around a uniform state with
// Jacobian J: the largest eigenvalue of J - l(l+1) diag(D). Measured as the log-slope of the
// perturbation's projection onto Y_l (mass-weighted) between two times.
struct HarmonicGrowth {
  double predicted;
  double measured;
};

HarmonicGrowth harmonic_growth(const json& scene, int l, const Eigen::Matrix2d& jacobian, const Eigen::Vector2d& state,
                               const Eigen::Vector2d& diffusion, double t_start, double t_end) {
  auto rd = load_rd_system(scene);
  const auto p = vertex_positions(rd.surface);
  // Zonal harmonics (Legendre polynomials in z = cos(theta)): eigenfunctions of -Laplacian with
  // eigenvalue l(l+1) on the unit sphere.
  auto legendre = [l](double z) {
    switch (l) {
      case 3: return (5 * z * z * z - 3 * z) / 2;
      case 4: return (35 * z * z * z * z - 30 * z * z + 3) / 8;
      default: throw std::logic_error("degree");
    }
  };
  const double q2 = l * (l + 1);
  const Eigen::Matrix2d a = jacobian - q2 * Eigen::Matrix2d(diffusion.asDiagonal());
  Eigen::EigenSolver<Eigen::Matrix2d> eig(a);
  int top = eig.eigenvalues().real()[0] > eig.eigenvalues().real()[1] ? 0 : 1;
  EXPECT_EQ(eig.eigenvalues().imag()[top], 0.0);
  const Eigen::Vector2d e = eig.eigenvectors().col(top).real();
  std::vector<double> y;
  for (const auto& q : p) y.push_back(legendre(q.z() / q.norm()));
  const double eps = 1e-6;
  for (size_t m = 0; m < 2; ++m)
    for (size_t i = 0; i < y.size(); ++i) rd.system.initial[m][i] = state[static_cast<Eigen::Index>(m)] + eps * e[static_cast<Eigen::Index>(m)] * y[i];
  ReferenceReactionDiffusion sim(rd.system);
  // The projection of the perturbation (of the morphogen with the larger eigenvector component).
  const size_t m = std::abs(e[0]) > std::abs(e[1]) ? 0 : 1;
  auto projection = [&] {
    double c = 0.0, norm = 0.0;
    for (size_t i = 0; i < y.size(); ++i) {
      c += rd.system.mass[i] * (sim.field(static_cast<int>(m))[i] - state[static_cast<Eigen::Index>(m)]) * y[i];
      norm += rd.system.mass[i] * y[i] * y[i];
    }
    return c / norm;
  };
  const double dt = rd.system.time_step;
  sim.run(std::llround(t_start / dt));
  const double c0 = projection();
  sim.run(std::llround((t_end - t_start) / dt));
  const double c1 = projection();
  return {eig.eigenvalues().real()[top], std::log(c1 / c0) / (t_end - t_start)};
}

TEST(ReactionDiffusionReference, SphericalHarmonicsGrowAndDecayAtTheLinearStabilityRate) {
  // Stable: Gray-Scott at (1, 0), degree 3. J = [[-F, 0], [0, -(F + k)]] (the u v^2 terms vanish
  // with v), so the v-mode decays at -(F + k) - 12 D_v.
  {
    const double F = 0.04, k = 0.06, Du = 0.02, Dv = 0.01;
    const json scene = {{"mesh", "shape:sphere"},
                        {"time_step", 0.01},
                        {"model", "gray-scott"},
                        {"parameters", {{"F", F}, {"k", k}}},
                        {"morphogens", {{"u", {{"diffusion", Du}}}, {"v", {{"diffusion", Dv}}}}}};
    Eigen::Matrix2d j;
    j << -F, 0.0, 0.0, -(F + k);
    const HarmonicGrowth g = harmonic_growth(scene, 3, j, {1.0, 0.0}, {Du, Dv}, 0.5, 5.0);
    RecordProperty("gray_scott_l3_measured", std::to_string(g.measured));
    EXPECT_NEAR(g.predicted, -(F + k) - 12 * Dv, 1e-12);
    EXPECT_NEAR(g.measured, g.predicted, 0.02 * std::abs(g.predicted)) << "predicted " << g.predicted;
  }
  // Unstable: Turing at (4, 4) with rho = 1, alpha = 16, beta = 12: J = rho [[-v, -u], [v, u - 1]]
  // = [[-4, -4], [4, 3]]; D_u / D_v = 8 (above the critical 4) makes degree 4 grow.
  {
    const double Du = 0.16, Dv = 0.02;
    const json scene = {{"mesh", "shape:sphere"},
                        {"time_step", 0.01},
                        {"model", "turing"},
                        {"parameters", {{"rho", 1.0}, {"alpha", 16.0}, {"beta", 12.0}}},
                        {"morphogens", {{"u", {{"diffusion", Du}}}, {"v", {{"diffusion", Dv}}}}}};
    Eigen::Matrix2d j;
    j << -4.0, -4.0, 4.0, 3.0;
    const HarmonicGrowth g = harmonic_growth(scene, 4, j, {4.0, 4.0}, {Du, Dv}, 0.5, 4.0);
    RecordProperty("turing_l4_predicted", std::to_string(g.predicted));
    RecordProperty("turing_l4_measured", std::to_string(g.measured));
    EXPECT_GT(g.predicted, 0.1);
    EXPECT_NEAR(g.measured, g.predicted, 0.02 * std::abs(g.predicted)) << "predicted " << g.predicted;
  }
}

TEST(ReactionDiffusionReference, TuringThresholdSeparatesDecayFromGrowth) {
  // Turk's model at (4, 4), alpha = 16, beta = 12: J = rho [[a, b], [c, d]] = rho [[-4, -4], [4, 3]].
  // With D_u = r D_v, a mode q^2 grows when det(J - q^2 D) < 0; the smallest det over q^2 is
  // negative exactly when (a + r d)^2 > 4 r (a d - b c), so the critical ratio is the larger root of
  // d^2 r^2 + (2 a d - 4 det J) r + a^2 = 0, and the critical mode q_c^2 = rho sqrt(det J / (r_c D_v^2)).
  const double a = -4, b = -4, c = 4, d = 3, det = a * d - b * c;
  const double qa = d * d, qb = 2 * a * d - 4 * det, qc = a * a;
  const double r_critical = (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
  EXPECT_NEAR(r_critical, 4.0, 1e-12);
  // D_v chosen so that the critical mode is degree 6 of the unit sphere (q^2 = 42).
  const double rho = 1.0, Dv = rho * std::sqrt(det / r_critical) / 42.0;
  auto variance_growth = [&](double ratio) {
    const json scene = {{"mesh", "shape:sphere"},
                        {"time_step", 0.05},
                        {"integrator", "imex"},
                        {"model", "turing"},
                        {"parameters", {{"rho", rho}, {"alpha", 16.0}, {"beta", 12.0}}},
                        {"initial", {{"noise", 1e-4}}},
                        {"morphogens", {{"u", {{"diffusion", ratio * Dv}}}, {"v", {{"diffusion", Dv}}}}}};
    const auto rd = load_rd_system(scene);
    ReferenceReactionDiffusion sim(rd.system);
    sim.run(100);  // 5 s: the fast-decaying modes are gone
    const double v0 = variance(sim.field(0), rd.system.mass);
    sim.run(600);  // 30 s more
    return variance(sim.field(0), rd.system.mass) / v0;
  };
  const double below = variance_growth(0.9 * r_critical), above = variance_growth(1.1 * r_critical);
  RecordProperty("variance_ratio_below", std::to_string(below));
  RecordProperty("variance_ratio_above", std::to_string(above));
  EXPECT_LT(below, 0.5);  // decays
  EXPECT_GT(above, 5.0);  // grows
}

TEST(ReactionDiffusionReference, ExplicitSubstepsKeepAStepBeyondTheLimitStable) {
  // Pure diffusion (no reaction) at 1.01 x the largest stable forward-Euler step, computed here by a
  // dense eigen-solve: the fastest mode is amplified by |1 - 1.01 x 2| = 1.02 per step without
  // sub-steps (1500 steps: 8e12), and damped with the automatic ones.
  json scene = {{"mesh", "shape:square"},
                {"reaction", {{"u", "0"}, {"v", "0"}}},
                {"initial", {{"noise", 1.0}}},
                {"morphogens", {{"u", {{"diffusion", 1e-3}}}, {"v", {{"diffusion", 2e-3}}}}}};
  scene["time_step"] = 1.0;
  const auto probe = load_rd_system(scene);
  const Eigen::MatrixXd k = Eigen::MatrixXd(probe.system.stiffness[1].to_eigen());
  Eigen::VectorXd s(k.rows());
  for (Eigen::Index i = 0; i < k.rows(); ++i) s[i] = 1.0 / std::sqrt(probe.system.mass[static_cast<size_t>(i)]);
  const double limit = 2.0 / Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(s.asDiagonal() * k * s.asDiagonal()).eigenvalues().maxCoeff();
  scene["time_step"] = 1.01 * limit;
  const auto rd = load_rd_system(scene);
  EXPECT_GE(rd.system.substeps, 2);
  // Stable diffusion never increases the M-norm (sum of mass x value^2); the initial noise is O(1).
  auto m_norm = [&](const IntrinsicVertexData<double>& u) {
    double sum = 0.0;
    for (size_t i = 0; i < u.size(); ++i) sum += rd.system.mass[i] * u[i] * u[i];
    return std::sqrt(sum);
  };
  const double start = m_norm(rd.system.initial[1]);
  ReferenceReactionDiffusion stepped(rd.system);
  stepped.run(1500);
  EXPECT_LE(m_norm(stepped.field(1)), start);
  ReactionDiffusionSystem single = rd.system;
  single.substeps = 1;
  ReferenceReactionDiffusion unstepped(single);
  unstepped.run(1500);
  EXPECT_GT(m_norm(unstepped.field(1)), 1e6 * start);
}

TEST(ReactionDiffusionReference, DirichletVerticesNeverMove) {
  // Gray-Scott seeded everywhere with spots, a band held at (1, 0.3): those vertices keep exactly
  // their values under both integrators while the rest evolves.
  for (const char* integrator : {"forward", "imex"}) {
    const json scene = {{"mesh", "shape:square"},
                        {"scale_to_area", 0.04},
                        {"time_step", 1.0},
                        {"integrator", integrator},
                        {"model", "gray-scott"},
                        {"maps", {{"band", {{"box", {{"min", {0.0, 0.0, -1.0}}, {"max", {0.2, 1.0, 1.0}}}}}}}},
                        {"initial", {{"noise", 0.05}}},
                        {"dirichlet", {{"map", "band"}, {"values", {{"u", 1.0}, {"v", 0.3}}}}}};
    const auto rd = load_rd_system(scene);
    ReferenceReactionDiffusion sim(rd.system);
    sim.run(200);
    int fixed = 0;
    double moved = 0.0;
    for (size_t i = 0; i < rd.system.fixed.size(); ++i) {
      if (rd.system.fixed[i]) {
        ++fixed;
        EXPECT_EQ(sim.field(0)[i], 1.0) << integrator;
        EXPECT_EQ(sim.field(1)[i], 0.3) << integrator;
      } else {
        moved = std::max(moved, std::abs(sim.field(1)[i] - rd.system.initial[1][i]));
      }
    }
    EXPECT_GT(fixed, 20);
    EXPECT_GT(moved, 1e-3) << integrator;
  }
}

}  // namespace
}  // namespace physarum
