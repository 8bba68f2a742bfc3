// Resolution independence, the point of the intrinsic framework: a Gray-Scott pattern grown on the
// same surface at two refinement levels has the same dominant wavelength (the peak of its radially
// averaged power spectrum) within 5 %, because the cotan Laplacian with lumped mass converges to the
// Laplace-Beltrami operator. The connectivity ("umbrella") Laplacian of graph-based tools, calibrated
// once on the coarse mesh as their users do, does not: its diffusion is counted in edges, so refining
// the mesh shrinks the pattern with the edges, and the same 5 % check fails. The same agreement is
// checked on a curved surface, the unit sphere, by the power per spherical-harmonic degree.
//
// Both levels start from the SAME continuum initial state: (1, 0) with seeds (u, v) = (1/2, 1/4)
// where a smooth random field w(x) (a sum of plane waves of one wavelength, 0.5 m, random directions
// and phases; unit variance) exceeds 1/2. Per-vertex noise would be a different realisation at each
// level; this way the two runs approximate one solution of the PDE, and the comparison measures the
// discretisation, not the luck of the draw. The seeds' own wavelength is 2.4 times the pattern's,
// so its spectrum (radii <= 2 cycles per side, and its harmonics, weaker) is left below the search.
//
// Regime: Pearson's diffusion ratio (D_u = 2 D_v) at F = 0.0545, k = 0.062, the "coral" stripes that
// invade (1, 0) from the seeds and fill the square with a labyrinth of one well-defined period.
// D_v = 2e-5 m^2/s gives about 0.21 m on the 1 m square (radius ~4.8 cycles per side), resolved by
// 10 (coarse, circumradius 0.012 m, ~4,200 vertices) and 14 (fine, 0.0085 m, ~8,300) vertices per
// wavelength. IMEX, dt = 2 (dt (F + k) = 0.23, the explicit reaction well inside its range). By
// t = 2500 (290 reaction times 1 / (F + k)) the stripes cover the square (v > 0.1 on ~2/3 of it, the
// stripes' duty cycle); the wavelengths are compared at t = 5000, when the labyrinth has settled
// (earlier, the still-moving fronts make the agreement depend on the seed layout: see Validation).
// Margin: this pair measures 0.2029 vs 0.2061 m (1.6 %). Why not coarser: at 7 vertices per
// wavelength the P1 dispersion alone is ~(2 pi / 7)^2 / 24 = 3.4 % in wavenumber, and six seed fields
// measured 0-4.4 % there, too close to 5 % for a check; at 10 it is 1.6 %. The Validation suite runs
// five other seed fields at this pair (within 2.6 %).
#include "pattern_spectrum.hpp"
#include "reaction_diffusion_scene.hpp"
#include "reference/reaction_diffusion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>

namespace physarum {
namespace {

using nlohmann::json;

constexpr double kDv = 2e-5, kDu = 2 * kDv;
constexpr double kCoarse = 0.012, kFine = 0.0085;  // max_circumradius, m
constexpr int kSettledSteps = 2500;                // t = 5000: the labyrinth has settled
constexpr int kGrownSteps = 1250;                  // t = 2500: it has filled the square

// The smooth random field w(x) = sqrt(2 / n) sum_j cos(k_j . x + phase_j), |k_j| fixed: mean 0,
// variance 1, a function of the position only (the same at every refinement).
class PlaneWaveField {
 public:
  PlaneWaveField(double wavenumber, int waves, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    for (int i = 0; i < waves; ++i) {
      const double a = angle(rng);
      k_.emplace_back(wavenumber * std::cos(a), wavenumber * std::sin(a));
      phase_.push_back(angle(rng));
    }
  }
  double operator()(const Eigen::Vector2d& x) const {
    double s = 0.0;
    for (size_t i = 0; i < k_.size(); ++i) s += std::cos(k_[i].dot(x) + phase_[i]);
    return s * std::sqrt(2.0 / static_cast<double>(k_.size()));
  }

 private:
  std::vector<Eigen::Vector2d> k_;
  std::vector<double> phase_;
};

struct Level {
  testing::LoadedReactionDiffusion rd;
  int vertices = 0;
};

// Pearson's square at one refinement, seeded as described above.
Level coral_square(double max_circumradius, unsigned seed_field = 7) {
  const json scene = {{"mesh", "shape:square"},
                      {"max_circumradius", max_circumradius},
                      {"time_step", 2.0},
                      {"integrator", "imex"},
                      {"model", "gray-scott"},
                      {"parameters", {{"F", 0.0545}, {"k", 0.062}}},
                      {"morphogens", {{"u", {{"diffusion", kDu}}}, {"v", {{"diffusion", kDv}}}}}};
  Level level{testing::load_rd_system(scene), 0};
  level.vertices = level.rd.surface.domain.vertex_count;
  const auto xy = planar_vertex_coordinates(level.rd.surface.domain, level.rd.surface.simulated);
  const PlaneWaveField w(2.0 * std::numbers::pi / 0.5, 12, seed_field);
  for (size_t i = 0; i < xy.size(); ++i)
    if (w(xy[i]) > 0.5) level.rd.system.initial[0][i] = 0.5, level.rd.system.initial[1][i] = 0.25;
  return level;
}

// The dominant wavelength (m) of u after `steps` steps (dt = 2).
double grown_wavelength(const Level& level, const ReactionDiffusionSystem& system, int steps) {
  ReferenceReactionDiffusion sim(system);
  sim.run(steps);
  return 2.0 * std::numbers::pi / testing::radial_peak(level.rd.surface, sim.field(0), 128, 3).wavenumber;
}

TEST(ReactionDiffusionResolution, GrayScottWavelengthIsTheSameAtTwoRefinements) {
  const Level coarse = coral_square(kCoarse), fine = coral_square(kFine);
  ASSERT_GT(fine.vertices, 1.8 * coarse.vertices);
  const double a = grown_wavelength(coarse, coarse.rd.system, kSettledSteps), b = grown_wavelength(fine, fine.rd.system, kSettledSteps);
  RecordProperty("vertices", std::to_string(coarse.vertices) + " " + std::to_string(fine.vertices));
  RecordProperty("wavelength_coarse", std::to_string(a));
  RecordProperty("wavelength_fine", std::to_string(b));
  // A pattern, not the seeds: between 3 and 8 cycles across the square.
  EXPECT_GT(a, 1.0 / 8.0);
  EXPECT_LT(a, 1.0 / 3.0);
  EXPECT_NEAR(b / a, 1.0, 0.05);
}

TEST(ReactionDiffusionResolution, ConnectivityLaplacianWavelengthChangesWithRefinement) {
  // The same two runs with the graph Laplacian, its scale fixed on the coarse mesh: the wavelength
  // follows the edge length (fine edges are 0.7 of the coarse ones), so the check above fails; the
  // effect (~30 %) is plain by t = 2500 already.
  const Level coarse = coral_square(kCoarse), fine = coral_square(kFine);
  const double scale = testing::connectivity_scale_matching(coarse.rd.surface.domain);
  ReactionDiffusionSystem graph_coarse = coarse.rd.system, graph_fine = fine.rd.system;
  testing::use_connectivity_laplacian(graph_coarse, coarse.rd.surface.domain, {kDu, kDv}, scale);
  testing::use_connectivity_laplacian(graph_fine, fine.rd.surface.domain, {kDu, kDv}, scale);
  const double a = grown_wavelength(coarse, graph_coarse, kGrownSteps), b = grown_wavelength(fine, graph_fine, kGrownSteps);
  RecordProperty("wavelength_coarse", std::to_string(a));
  RecordProperty("wavelength_fine", std::to_string(b));
  EXPECT_GT(std::abs(b / a - 1.0), 0.05);
}

// Validation (label `validation`): the two checks above for five more seed fields at the same levels
// (10 and 14 vertices per wavelength), so the CI case is not a lucky layout. Measured: within 2.6 %
// (102 s on 2 busy cores); at 7 and 10 vertices per wavelength the same seeds agreed only within 0.2
// to 4.4 % at t = 5000 (and within 7 % at t = 2500, before the labyrinth settles). Every seed must
// pass both checks.
TEST(ValidationReactionDiffusionResolution, FlatSquareAgreementHoldsForOtherSeedFields) {
  double worst_cotan = 0.0, least_graph = 1e9;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE("seed field " + std::to_string(seed));
    const Level coarse = coral_square(kCoarse, seed), fine = coral_square(kFine, seed);
    const double cotan = grown_wavelength(fine, fine.rd.system, kSettledSteps) /
                         grown_wavelength(coarse, coarse.rd.system, kSettledSteps);
    const double scale = testing::connectivity_scale_matching(coarse.rd.surface.domain);
    ReactionDiffusionSystem graph_coarse = coarse.rd.system, graph_fine = fine.rd.system;
    testing::use_connectivity_laplacian(graph_coarse, coarse.rd.surface.domain, {kDu, kDv}, scale);
    testing::use_connectivity_laplacian(graph_fine, fine.rd.surface.domain, {kDu, kDv}, scale);
    const double graph = grown_wavelength(fine, graph_fine, kGrownSteps) / grown_wavelength(coarse, graph_coarse, kGrownSteps);
    EXPECT_NEAR(cotan, 1.0, 0.05);
    EXPECT_GT(std::abs(graph - 1.0), 0.05);
    worst_cotan = std::max(worst_cotan, std::abs(cotan - 1.0));
    least_graph = std::min(least_graph, std::abs(graph - 1.0));
  }
  RecordProperty("worst_cotan_deviation", std::to_string(worst_cotan));
  RecordProperty("least_connectivity_deviation", std::to_string(least_graph));
}

// ---- a curved surface ----
//
// The same regime on the unit sphere, measured by the power per spherical-harmonic degree: the
// coarse level is shape:sphere itself (2,562 vertices, edges ~0.076 m), the fine one its intrinsic
// refinement. D_v = 1.5e-4 m^2/s scales the flat square's 0.21 m wavelength by sqrt(7.5) to about
// 0.57 m (degree ~11, 7.5 coarse edges per wavelength). The seeds are plane waves in 3D restricted
// to the sphere (wavelength 1.4 m: degrees <= 4), above 1/2 as on the square.
struct SphereLevel {
  testing::LoadedReactionDiffusion rd;
  std::vector<Eigen::Vector3d> position;
};

SphereLevel coral_sphere(std::optional<double> max_circumradius) {
  constexpr double dv = 1.5e-4;
  json scene = {{"mesh", "shape:sphere"},
                {"time_step", 2.0},
                {"integrator", "imex"},
                {"model", "gray-scott"},
                {"parameters", {{"F", 0.0545}, {"k", 0.062}}},
                {"morphogens", {{"u", {{"diffusion", 2 * dv}}}, {"v", {{"diffusion", dv}}}}}};
  if (max_circumradius) scene["max_circumradius"] = *max_circumradius;
  SphereLevel level{testing::load_rd_system(scene), {}};
  level.position = testing::vertex_positions(level.rd.surface);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
  std::vector<Eigen::Vector3d> k;
  std::vector<double> phase;
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    k.push_back(2.0 * std::numbers::pi / 1.4 * d.normalized());
    phase.push_back(angle(rng));
  }
  for (size_t i = 0; i < level.position.size(); ++i) {
    double w = 0.0;
    for (size_t j = 0; j < k.size(); ++j) w += std::cos(k[j].dot(level.position[i]) + phase[j]);
    if (w * std::sqrt(2.0 / static_cast<double>(k.size())) > 0.5)
      level.rd.system.initial[0][i] = 0.5, level.rd.system.initial[1][i] = 0.25;
  }
  return level;
}

// The dominant wavenumber (rad/m) of u after t = 2500 (agreement is already 0.03 % there), peak
// searched over degrees 5 to 24.
double grown_sphere_wavenumber(const SphereLevel& level) {
  ReferenceReactionDiffusion sim(level.rd.system);
  sim.run(kGrownSteps);
  return testing::spherical_peak(level.position, level.rd.system.mass, sim.field(0), 1.0, 24, 5).wavenumber;
}

TEST(ReactionDiffusionResolution, GrayScottWavenumberOnTheSphereIsTheSameAtTwoRefinements) {
  const SphereLevel coarse = coral_sphere(std::nullopt), fine = coral_sphere(0.041);
  ASSERT_GT(fine.position.size(), 1.6 * coarse.position.size());
  const double a = grown_sphere_wavenumber(coarse), b = grown_sphere_wavenumber(fine);
  RecordProperty("vertices", std::to_string(coarse.position.size()) + " " + std::to_string(fine.position.size()));
  RecordProperty("wavenumber_coarse", std::to_string(a));
  RecordProperty("wavenumber_fine", std::to_string(b));
  EXPECT_GT(a, std::sqrt(6.0 * 7.0));  // a pattern, not the seeds (degrees <= 4)
  EXPECT_NEAR(b / a, 1.0, 0.05);
}

}  // namespace
}  // namespace physarum
