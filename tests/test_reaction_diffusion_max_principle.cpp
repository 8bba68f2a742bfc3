// The Fig. 4 effect for reaction-diffusion: on shape:skinny-sphere (long thin triangles whose
// extrinsic cotan weights are negative) Gray-Scott on the intrinsic Delaunay triangulation keeps its
// invariant region, while the same system on the input triangulation leaves it.
//
// The known answer: for Gray-Scott the continuum keeps 0 <= u <= 1 and v >= 0 (at u = 1 the
// u-reaction -u v^2 + F (1 - u) <= 0, at v = 0 the v-reaction vanishes). The discrete scheme keeps it
// too when the stiffness is an M-matrix (off-diagonals <= 0, i.e. non-negative cotan weights, which
// intrinsic Delaunay guarantees):
//   IMEX      the explicit reaction maps the region into itself for dt (v^2 + F) <= 1, and
//             (M + dt K)^-1 M is then entrywise >= 0 with unit row sums, so the implicit diffusion
//             takes convex combinations: no new extrema, for every dt;
//   explicit  u_i - h (M^-1 K u)_i is a convex combination of u_i and its neighbours while
//             h <= m_i / K_ii, so a sub-step below that bound keeps the region too.
// With a negative weight w_ij both arguments fail: a spike at i pushes its neighbour j below its
// surroundings. The spike sits at an end of the most negative extrinsic edge, as in
// test_fe_operators' pure-diffusion version of Fig. 4.
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/setup/reaction_diffusion_build.hpp"
#include "reaction_diffusion_scene.hpp"
#include "reference/reaction_diffusion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {
namespace {

using nlohmann::json;

constexpr double kDu = 2e-3, kDv = 1e-3;  // on the unit sphere: a spot spreads over a few rings in tens of steps

// The most positive off-diagonal entry of K, i.e. the most negative cotan weight (K_ij = -D w_ij):
// its row (where the spike goes) and its value (> 0 exactly when some weight is negative).
std::pair<int, double> most_negative_weight(const CsrMatrix& k) {
  std::pair<int, double> worst{-1, -std::numeric_limits<double>::infinity()};
  for (int i = 0; i < k.rows; ++i)
    for (int e = k.row_start[static_cast<size_t>(i)]; e < k.row_start[static_cast<size_t>(i) + 1]; ++e)
      if (k.column[static_cast<size_t>(e)] != i && k.value[static_cast<size_t>(e)] > worst.second)
        worst = {i, k.value[static_cast<size_t>(e)]};
  return worst;
}

struct InvariantRegionExcursion {
  double u_above_one = 0.0;  // max(u - 1) over vertices and steps, if positive
  double u_below_zero = 0.0; // max(-u)
  double v_below_zero = 0.0; // max(-v)
  double worst() const { return std::max({u_above_one, u_below_zero, v_below_zero}); }
};

InvariantRegionExcursion run_and_track(const ReactionDiffusionSystem& system, int steps) {
  ReferenceReactionDiffusion sim(system);
  InvariantRegionExcursion e;
  for (int s = 0; s < steps; ++s) {
    sim.step();
    for (const double u : sim.field(0)) e.u_above_one = std::max(e.u_above_one, u - 1.0), e.u_below_zero = std::max(e.u_below_zero, -u);
    for (const double v : sim.field(1)) e.v_below_zero = std::max(e.v_below_zero, -v);
  }
  return e;
}

struct SkinnySystems {
  ReactionDiffusionSystem intrinsic, extrinsic;
  int spike = -1;
  double extrinsic_worst_weight = 0.0, intrinsic_worst_weight = 0.0;
};

// Gray-Scott (Pearson's F, k) at (1, 0) with the spike (u, v) = (0, 1) on the skinny sphere, on the
// intrinsic Delaunay triangulation (what a scene runs on) and on the input triangulation itself.
SkinnySystems skinny_systems(const char* integrator, double time_step) {
  const json scene = {{"mesh", "shape:skinny-sphere"},
                      {"time_step", time_step},
                      {"integrator", integrator},
                      {"model", "gray-scott"},
                      {"parameters", {{"F", 0.04}, {"k", 0.06}}},
                      {"morphogens", {{"u", {{"diffusion", kDu}}}, {"v", {{"diffusion", kDv}}}}}};
  const auto rd = testing::load_rd_system(scene);
  SkinnySystems s;
  s.intrinsic = rd.system;
  // The input triangulation as a domain of its own: same vertices (no refinement was asked), the
  // extrinsic edges and their cotan weights.
  const SurfaceDomain extrinsic = build_surface_domain(intrinsic_mesh_from_input(rd.surface.simulated));
  EXPECT_EQ(extrinsic.vertex_count, rd.surface.domain.vertex_count);
  s.extrinsic = rd.system;
  s.extrinsic.mass = extrinsic.vertex_mass;
  s.extrinsic.stiffness = {diffusion_stiffness(extrinsic, IntrinsicVertexData<double>(static_cast<size_t>(extrinsic.vertex_count), kDu)),
                           diffusion_stiffness(extrinsic, IntrinsicVertexData<double>(static_cast<size_t>(extrinsic.vertex_count), kDv))};
  const auto [spike, weight] = most_negative_weight(s.extrinsic.stiffness[1]);
  s.spike = spike;
  s.extrinsic_worst_weight = weight;
  s.intrinsic_worst_weight = most_negative_weight(s.intrinsic.stiffness[1]).second;
  for (ReactionDiffusionSystem* system : {&s.intrinsic, &s.extrinsic}) {
    system->initial[0][static_cast<size_t>(spike)] = 0.0;
    system->initial[1][static_cast<size_t>(spike)] = 1.0;
  }
  return s;
}

TEST(ReactionDiffusionMaxPrinciple, SkinnySphereImexKeepsTheInvariantRegionOnlyIntrinsically) {
  for (const double dt : {0.25, 0.9}) {
    SCOPED_TRACE("dt " + std::to_string(dt));
    const SkinnySystems s = skinny_systems("imex", dt);
    // The premise: the extrinsic stiffness has a clearly positive off-diagonal (negative weight),
    // the intrinsic one none beyond round-off.
    ASSERT_GT(s.extrinsic_worst_weight, 1e-3 * kDv);
    ASSERT_LE(s.intrinsic_worst_weight, 1e-12 * kDv);
    // Both steps are below 1 / (1 + F): the explicit reaction alone stays in the region (v <= 1).
    const InvariantRegionExcursion intrinsic = run_and_track(s.intrinsic, 40);
    const InvariantRegionExcursion extrinsic = run_and_track(s.extrinsic, 40);
    RecordProperty("extrinsic_excursion_dt" + std::to_string(static_cast<int>(dt * 100)), std::to_string(extrinsic.worst()));
    EXPECT_LE(intrinsic.worst(), 1e-12);
    EXPECT_GT(extrinsic.v_below_zero, 1e-4);
  }
}

TEST(ReactionDiffusionMaxPrinciple, SkinnySphereExplicitKeepsTheInvariantRegionOnlyIntrinsically) {
  // One sub-step per step, h = 0.9 min_i m_i / K_ii of the faster morphogen on each triangulation:
  // below the convex-combination bound on both, so only the signs of the weights differ.
  for (const bool intrinsic_side : {true, false}) {
    SkinnySystems s = skinny_systems("forward", 1.0);
    ReactionDiffusionSystem& system = intrinsic_side ? s.intrinsic : s.extrinsic;
    double bound = std::numeric_limits<double>::infinity();
    const CsrMatrix& k = system.stiffness[0];
    for (int i = 0; i < k.rows; ++i)
      for (int e = k.row_start[static_cast<size_t>(i)]; e < k.row_start[static_cast<size_t>(i) + 1]; ++e)
        if (k.column[static_cast<size_t>(e)] == i) bound = std::min(bound, system.mass[static_cast<size_t>(i)] / k.value[static_cast<size_t>(e)]);
    system.time_step = 0.9 * bound;
    system.substeps = 1;
    const InvariantRegionExcursion e = run_and_track(system, 200);
    RecordProperty(intrinsic_side ? "intrinsic_excursion" : "extrinsic_excursion", std::to_string(e.worst()));
    if (intrinsic_side) EXPECT_LE(e.worst(), 1e-12) << "h " << system.time_step;
    else EXPECT_GT(e.v_below_zero, 1e-4) << "h " << system.time_step;
  }
}

}  // namespace
}  // namespace physarum
