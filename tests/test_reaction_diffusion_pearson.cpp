// Pearson's classic Gray-Scott experiment (Science 261, 1993) on shape:square with the reference
// backend: D_u = 2e-5, D_v = 1e-5, F = 0.04, k = 0.06, the trivial state (1, 0) everywhere except a
// central square of Pearson's size (20 of his 256 cells on 2.5 m: 0.195 m) set to (1/2, 1/4) with
// 1 % noise. The square is 0.5 m here (his cell size, 0.0098 m, kept by the refinement bound) so
// the run takes seconds.
//
// Spreading: at k = 0.06 (on the saddle-node line k = sqrt(F)/2 - F, Pearson's spot-replication
// regime) the seeded region replicates spots outward. The seed covers 15 % of the square; after
// 4000 time units (400 reaction times 1/(F + k)) the pattern must cover more than three times that
// (v > 0.1 on more than 50 % of the area; measured: 70 %) and still be a pattern (not uniform: at
// most 95 %). A v without its autocatalysis (a broken reaction term) covers 0 %.
// Dying out: at k = 0.075, well above sqrt(F)/2 - F = 0.06, (1, 0) is the only uniform state and it
// is linearly stable, so the same seed decays: v < 1e-3 everywhere at the same time.
#include "reaction_diffusion_scene.hpp"
#include "reference/reaction_diffusion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;

json pearson(double k) {
  return {{"mesh", "shape:square"},
          {"scale_to_area", 0.25},
          {"max_circumradius", 0.0098},
          {"time_step", 1.0},
          {"model", "gray-scott"},
          {"parameters", {{"F", 0.04}, {"k", k}}},
          {"morphogens", {{"u", {{"diffusion", 2e-5}}}, {"v", {{"diffusion", 1e-5}}}}},
          // The square's input coordinates are 0..1 before scaling: the centre 0.39 of them is 0.195 m.
          {"maps", {{"centre", {{"box", {{"min", {0.305, 0.305, -1.0}}, {"max", {0.695, 0.695, 1.0}}}}}}}},
          {"initial", {{"noise", 0.01}, {"seed_region", {{"map", "centre"}, {"values", {{"u", 0.5}, {"v", 0.25}}}}}}}};
}

double coverage(const IntrinsicVertexData<double>& v, const IntrinsicVertexData<double>& mass, double threshold) {
  double covered = 0.0, area = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    area += mass[i];
    if (v[i] > threshold) covered += mass[i];
  }
  return covered / area;
}

TEST(ReactionDiffusionPearson, SpotsSpreadFromTheCentralSquare) {
  const auto rd = testing::load_rd_system(pearson(0.06));
  ReferenceReactionDiffusion sim(rd.system);
  const double initial = coverage(sim.field(1), rd.system.mass, 0.1);
  EXPECT_NEAR(initial, 0.152, 0.03);
  sim.run(4000);
  const double grown = coverage(sim.field(1), rd.system.mass, 0.1);
  RecordProperty("coverage_initial", std::to_string(initial));
  RecordProperty("coverage_after_4000", std::to_string(grown));
  EXPECT_GT(grown, 0.50) << "from " << initial;
  EXPECT_LT(grown, 0.95);  // spots, not a uniform state
}

TEST(ReactionDiffusionPearson, ThePerturbationDiesWhereTheTrivialStateIsTheOnlyOne) {
  const double F = 0.04, k = 0.075;
  ASSERT_GT(k, std::sqrt(F) / 2 - F + 0.01);
  const auto rd = testing::load_rd_system(pearson(k));
  ReferenceReactionDiffusion sim(rd.system);
  sim.run(4000);
  const auto& v = sim.field(1);
  RecordProperty("max_v_after_4000", std::to_string(*std::max_element(v.begin(), v.end())));
  EXPECT_LT(*std::max_element(v.begin(), v.end()), 1e-3);
}

}  // namespace
}  // namespace physarum
