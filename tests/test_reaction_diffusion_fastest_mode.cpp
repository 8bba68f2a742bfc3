// Turing's model (Turk's form, Eq. 20 of `002_…`) grown from small noise around its unstable uniform
// state: the pattern's spectral peak sits at the fastest-growing wavenumber that linear stability of
// the CONTINUUM equations predicts, on a flat square (radial FFT spectrum) and on the unit sphere
// (power per spherical-harmonic degree). A scheme whose diffusion is not the Laplace-Beltrami
// operator of the surface (a connectivity Laplacian) puts the peak elsewhere.
//
// The prediction, derived here: around (u0, v0) = (alpha / (alpha - beta), alpha - beta) a mode of
// wavenumber q (an eigenfunction of -Laplacian with eigenvalue q^2) evolves by
//   d/dt (du, dv) = (J - q^2 diag(D_u, D_v)) (du, dv),   J = rho [[-v0, -u0], [v0, u0 - 1]],
// so it grows at sigma(q^2) = the largest real part of that matrix's eigenvalues; the fastest mode
// q* maximises sigma. From white noise every mode starts with the same expected power and after time
// t has it times exp(2 sigma(q) t): the expected spectrum peaks at q* at every t, and sharpens with t.
// The run stays linear (noise 1e-9, grown by exp(sigma* t) ~ 5e6 at t = 20), so no nonlinear wavelength
// selection moves the peak.
//
// Tolerance 15 % (the issue's): the spectrum's bins are 1/side apart (12 % of q* on the square,
// degrees 8 and 9 are 11 % apart on the sphere) and sigma is flat near q*, so the peak of one noise
// realisation wanders by a fraction of a bin; the sub-bin centroid brings it to a few percent.
#include "pattern_spectrum.hpp"
#include "reaction_diffusion_scene.hpp"
#include "reference/reaction_diffusion.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;

constexpr double kRho = 1.0, kAlpha = 16.0, kBeta = 12.0;

// sigma(q^2) as defined above.
double growth_rate(double q2, double du, double dv) {
  const double v0 = kAlpha - kBeta, u0 = kAlpha / v0;
  Eigen::Matrix2d a;
  a << -kRho * v0 - q2 * du, -kRho * u0, kRho * v0, kRho * (u0 - 1.0) - q2 * dv;
  return Eigen::EigenSolver<Eigen::Matrix2d>(a, false).eigenvalues().real().maxCoeff();
}

// q* (rad/m): sigma on a logarithmic scan of q^2, then golden-section search around the best point.
double fastest_wavenumber(double du, double dv) {
  double best = 1e-3, best_sigma = growth_rate(best, du, dv);
  for (double q2 = 1e-3; q2 < 1e7; q2 *= 1.01) {
    const double s = growth_rate(q2, du, dv);
    if (s > best_sigma) best = q2, best_sigma = s;
  }
  double lo = best / 1.01, hi = best * 1.01;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 100; ++i) {
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    if (growth_rate(a, du, dv) > growth_rate(b, du, dv)) hi = b;
    else lo = a;
  }
  return std::sqrt((lo + hi) / 2.0);
}

json turing_scene(const char* mesh, double du, double dv) {
  return {{"mesh", mesh},
          {"time_step", 0.05},
          {"integrator", "imex"},
          {"model", "turing"},
          {"parameters", {{"rho", kRho}, {"alpha", kAlpha}, {"beta", kBeta}}},
          {"initial", {{"noise", 1e-9}}},
          {"morphogens", {{"u", {{"diffusion", du}, {"initial", 4.0}}}, {"v", {{"diffusion", dv}, {"initial", 4.0}}}}}};
}

TEST(ReactionDiffusionFastestMode, TheDerivedFastestModeIsTheUnstableBandsMaximum) {
  // The derivation's own check: Turing's threshold (D_u / D_v = 4 for these kinetics, see
  // test_reaction_diffusion_reference) has sigma <= 0 everywhere at a ratio of 3 and a positive
  // maximum at 8, where the unstable band is det(J - q^2 D) < 0.
  const double dv = 3e-4;
  EXPECT_LT(growth_rate(fastest_wavenumber(3 * dv, dv) * fastest_wavenumber(3 * dv, dv), 3 * dv, dv), 0.0);
  const double q = fastest_wavenumber(8 * dv, dv);
  const double sigma = growth_rate(q * q, 8 * dv, dv);
  EXPECT_GT(sigma, 0.5);
  for (const double f : {0.9, 1.1}) EXPECT_LT(growth_rate(f * f * q * q, 8 * dv, dv), sigma);
  // With D_u = 8 D_v, det(J - q^2 D) = 8 s^2 - 20 s + 4 in s = D_v q^2: the band is s in
  // ((5 - sqrt(17)) / 4, (5 + sqrt(17)) / 4) and q* lies inside it.
  const double s = dv * q * q;
  EXPECT_GT(s, (5.0 - std::sqrt(17.0)) / 4.0);
  EXPECT_LT(s, (5.0 + std::sqrt(17.0)) / 4.0);
}

TEST(ReactionDiffusionFastestMode, FlatSquarePeaksAtTheFastestGrowingWavelength) {
  // D_u / D_v = 8 and D_v = 3e-4 m^2/s: q* = 52 rad/m, 8.3 wavelengths across the 1 m square; the
  // refinement gives about 9 vertices per wavelength.
  const double dv = 3e-4, du = 8 * dv;
  json scene = turing_scene("shape:square", du, dv);
  scene["max_circumradius"] = 0.008;
  const auto rd = testing::load_rd_system(scene);
  ReferenceReactionDiffusion sim(rd.system);
  sim.run(400);  // t = 20: sigma* t = 15
  const double predicted = fastest_wavenumber(du, dv);
  const auto measured = testing::radial_peak(rd.surface, sim.field(0), 128);
  RecordProperty("vertices", std::to_string(rd.surface.domain.vertex_count));
  RecordProperty("predicted_wavenumber", std::to_string(predicted));
  RecordProperty("measured_wavenumber", std::to_string(measured.wavenumber));
  EXPECT_NEAR(measured.wavenumber, predicted, 0.15 * predicted) << "peak bin " << measured.peak.bin;
}

// Validation (label `validation`): the flat square for five more noise seeds; every realisation's
// peak must be within the tolerance.
TEST(ValidationReactionDiffusionFastestMode, FlatSquarePeakHoldsForOtherNoiseSeeds) {
  const double dv = 3e-4, du = 8 * dv;
  const double predicted = fastest_wavenumber(du, dv);
  double worst = 0.0;
  for (int seed = 2; seed <= 6; ++seed) {
    json scene = turing_scene("shape:square", du, dv);
    scene["max_circumradius"] = 0.008;
    scene["seed"] = seed;
    const auto rd = testing::load_rd_system(scene);
    ReferenceReactionDiffusion sim(rd.system);
    sim.run(400);
    const double measured = testing::radial_peak(rd.surface, sim.field(0), 128).wavenumber;
    EXPECT_NEAR(measured, predicted, 0.15 * predicted) << "seed " << seed;
    worst = std::max(worst, std::abs(measured / predicted - 1.0));
  }
  RecordProperty("worst_relative_deviation", std::to_string(worst));
}

TEST(ReactionDiffusionFastestMode, SpherePeaksAtTheFastestGrowingDegree) {
  // Unit sphere (2562 vertices), D_v = 0.01: q*^2 = 82, between degrees 8 (72) and 9 (90).
  const double dv = 0.01, du = 8 * dv;
  const auto rd = testing::load_rd_system(turing_scene("shape:sphere", du, dv));
  ReferenceReactionDiffusion sim(rd.system);
  sim.run(400);
  const double predicted = fastest_wavenumber(du, dv);
  const auto measured = testing::spherical_peak(testing::vertex_positions(rd.surface), rd.system.mass, sim.field(0), 1.0, 20);
  RecordProperty("predicted_wavenumber", std::to_string(predicted));
  RecordProperty("measured_wavenumber", std::to_string(measured.wavenumber));
  RecordProperty("peak_degree", std::to_string(measured.peak.bin));
  EXPECT_NEAR(measured.wavenumber, predicted, 0.15 * predicted) << "peak degree " << measured.peak.bin;
}

}  // namespace
}  // namespace physarum
