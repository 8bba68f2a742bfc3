// `physarum run` on a reaction-diffusion scene has what an agent run has: a run killed with SIGKILL
// at a random moment and resumed from its checkpoint writes byte for byte what the uninterrupted run
// writes (both backends); --maps-out writes the scene's maps (checked against the map's definition,
// not against the code's output); a second run reads its maps from the map cache.
#include "cache_environment.hpp"
#include "common/ply_reader.hpp"
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

class ReactionDiffusionResume : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    std::ofstream(dir_.path / "scene.json") << rd_scene().dump();
    const CommandResult probe = run_physarum("run " + quoted(dir_.path / "scene.json") + " --backend " + GetParam() +
                                             " --steps 1 --texture-size 16 --out " + quoted(dir_.path / "probe"));
    if (probe.exit_code != 0 && probe.err.find("device error") != std::string::npos)
      GTEST_SKIP() << "no OpenCL device: " << probe.err;
    ASSERT_EQ(probe.exit_code, 0) << probe.err;
  }
  std::vector<std::string> run_args(const fs::path& out) const {
    return {"run", (dir_.path / "scene.json").string(), "--backend", GetParam(), "--steps", std::to_string(kSteps),
            "--texture-size", "16", "--out", out.string()};
  }
  TempDir dir_;
};

TEST_P(ReactionDiffusionResume, KilledRunResumesToTheUninterruptedRunsBytes) {
  std::string whole_args;
  for (const std::string& a : run_args(dir_.path / "whole")) whole_args += quoted(fs::path(a)) + " ";
  const CommandResult whole = run_physarum(whole_args);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;

  const unsigned seed = std::random_device{}();
  const fs::path killed = dir_.path / "killed";
  std::vector<std::string> args = run_args(killed);
  args.insert(args.end(), {"--checkpoint-every", "10"});  // every 10 steps
  ASSERT_TRUE(run_and_kill(args, killed / "checkpoint.bin", seed))
      << "the run finished before it could be killed (kill delay seed " << seed << ")";
  ASSERT_TRUE(fs::exists(killed / "checkpoint.bin"));
  ASSERT_FALSE(fs::exists(killed / "run.json"));

  const CommandResult resumed = run_physarum("run --resume " + quoted(killed));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  for (const char* file : {"pheromone.ply", "fields_full.ply", "stats.csv", "preview.png"})
    EXPECT_TRUE(bytes_of(killed / file) == bytes_of(dir_.path / "whole" / file))
        << file << " differs from the uninterrupted run's (kill delay seed " << seed << ")";
  std::ifstream in(killed / "run.json");
  const auto j = json::parse(in);
  const long long from = j["resumed_from_step"].get<long long>();
  EXPECT_GT(from, 0);
  EXPECT_LT(from, kSteps);
  EXPECT_EQ(from % 10, 0);
  EXPECT_EQ(j["steps"], kSteps);
  EXPECT_FALSE(fs::exists(killed / "checkpoint.bin")) << "a finished run removes its checkpoint";

  // A checkpoint of another scene (k changed) is refused, and nothing is written.
  ASSERT_TRUE(run_and_kill(args, killed / "checkpoint.bin", seed + 1));
  fs::remove(killed / "run.json");
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
// definition in DESIGN.md), and the range map lo + (hi - lo) x ramp; a second run takes both from
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
