// `physarum run` on a reaction-diffusion scene has what an agent run has: a run killed with SIGKILL
// at a random moment and resumed from its checkpoint writes byte for byte what the uninterrupted run
// writes (both backends); --maps-out writes the scene's maps (checked against the map's definition,
// not against the code's output); a second run reads its maps from the map cache.
#include "cache_environment.hpp"
#include "common/mesh/ply_reader.hpp"
#include "killed_run.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Pearson's spots on a small square: a few hundred vertices, so 20,000 steps take a fraction of a
// second and a checkpoint every 10 steps leaves a wide window to be killed in. The F map (a ramp
// along x) makes the run read a map, so a resume also rebuilds the maps.
json rd_scene() {
  return {{"mesh", "shape:square"},
          {"scale_to_area", 0.04},
          {"max_circumradius", 0.01},
          {"model", "gray-scott"},
          {"maps", {{"ramp", {{"axis", "x"}}}, {"feed", {{"map", "ramp"}, {"range", {0.03, 0.04}}}}}},
          {"parameters", {{"F", "feed"}, {"k", 0.06}}},
          {"morphogens", {{"u", {{"diffusion", 2e-5}, {"initial", 1.0}}}, {"v", {{"diffusion", 1e-5}, {"initial", 0.0}}}}},
          {"initial", {{"noise", 0.01}, {"spots", {{"count", 3}, {"radius", 0.02}, {"values", {{"u", 0.5}, {"v", 0.25}}}}}}},
          {"time_step", 1.0},
          {"seed", 3}};
}
constexpr int kSteps = 20000;

class ReactionDiffusionResume : public ResumeFixture {
 protected:
  void SetUp() override { prepare(rd_scene().dump(), kSteps); }
};

TEST_P(ReactionDiffusionResume, KilledRunResumesToTheUninterruptedRunsBytes) {
  expect_killed_run_resumes_to_the_same_bytes("10", 10);  // every 10 steps

  // A checkpoint of another scene (k changed) is refused, and nothing is written.
  const fs::path killed = dir_.path / "killed_again";
  std::vector<std::string> args = run_args(killed);
  args.insert(args.end(), {"--checkpoint-every", "10"});
  ASSERT_TRUE(run_and_kill(args, killed / "checkpoint.bin", 11));
  json other = rd_scene();
  other["parameters"]["k"] = 0.061;
  std::ofstream(dir_.path / "other.json") << other.dump();
  const CommandResult foreign = run_physarum("run " + quoted(dir_.path / "other.json") + " --resume " + quoted(killed));
  EXPECT_EQ(foreign.exit_code, 1);
  EXPECT_NE(foreign.err.find("another scene"), std::string::npos) << foreign.err;
  EXPECT_FALSE(fs::exists(killed / "run.json"));
}

INSTANTIATE_TEST_SUITE_P(Backends, ReactionDiffusionResume, ::testing::Values("reference", "opencl"));

// --maps-out: the ramp {"axis": "x"} is (x - x_min) / (x_max - x_min) at every input vertex (the
// definition in docs/maps.md), and the range map lo + (hi - lo) x ramp; a second run takes both from
// the cache.
TEST(ReactionDiffusionRun, MapsOutWritesTheScenesMapsAndASecondRunReadsTheCache) {
  TempDir dir;
  const CacheEnvironment cache(dir.path / "cache");
  std::ofstream(dir.path / "scene.json") << rd_scene().dump();
  const std::string args = "run " + quoted(dir.path / "scene.json") + " --backend reference --steps 2 --texture-size 16";
  const CommandResult first = run_physarum(args + " --out " + quoted(dir.path / "a") + " --maps-out " + quoted(dir.path / "maps.ply"));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.err.find("maps: 2 computed"), std::string::npos) << first.err;
  const PlyFields maps = read_ply_fields((dir.path / "maps.ply").string());
  const std::vector<double>& ramp = maps.property("ramp");
  const std::vector<double>& feed = maps.property("feed");
  ASSERT_EQ(ramp.size(), maps.mesh.positions.size());
  double low = 1e300, high = -1e300;
  for (const auto& p : maps.mesh.positions) {
    low = std::min(low, p.x());
    high = std::max(high, p.x());
  }
  for (size_t v = 0; v < ramp.size(); ++v) {
    const double expected = (maps.mesh.positions[v].x() - low) / (high - low);
    EXPECT_NEAR(ramp[v], expected, 1e-6) << "vertex " << v;
    EXPECT_NEAR(feed[v], 0.03 + 0.01 * expected, 1e-8) << "vertex " << v;
  }
  const CommandResult second = run_physarum(args + " --out " + quoted(dir.path / "b"));
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.err.find("maps: 2 from cache"), std::string::npos) << second.err;
}

}  // namespace
}  // namespace physarum::testing
