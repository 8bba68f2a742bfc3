// Fail fast on inputs that cannot work (common/setup/run_feasibility.hpp), through the command line as a
// user meets them: each scene below used to refine, allocate or simulate for minutes (or GBs)
// before failing or finishing with a meaningless result. Each is now refused (exit 1, nothing
// written, the message naming the numbers) or warned about, within seconds.
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/setup/run_feasibility.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace physarum {
namespace {

using testing::CommandResult;
using testing::TempDir;

constexpr double kMaxSeconds = 5.0;  // the old behaviour took from 40 s to minutes

struct Timed {
  CommandResult result;
  double seconds = 0.0;
};

// tools/scenes/default.json (the 4 m^2 sphere) with `changes` applied, run for `steps` steps.
Timed run_default_with(const TempDir& dir, const nlohmann::json& changes, const std::string& extra = "",
                       int steps = 3) {
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/default.json"));
  scene.update(changes);
  const std::filesystem::path path = dir.path / "scene.json";
  std::ofstream(path) << scene.dump(2);
  const auto start = std::chrono::steady_clock::now();
  Timed t;
  t.result = testing::run_physarum("run '" + path.string() + "' --steps " + std::to_string(steps) + " --out '" +
                                   (dir.path / "out").string() + "' " + extra);
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

// Refused: exit 1, every expected word in the message, nothing written, quickly.
void expect_refused(const TempDir& dir, const Timed& t, const std::vector<std::string>& words) {
  EXPECT_EQ(t.result.exit_code, 1) << t.result.err;
  for (const std::string& w : words) EXPECT_NE(t.result.err.find(w), std::string::npos) << "no '" << w << "' in:\n" << t.result.err;
  EXPECT_EQ(t.result.err.find("0.000000"), std::string::npos) << t.result.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "out")) << "a refused run wrote its output folder";
  EXPECT_LT(t.seconds, kMaxSeconds);
}

TEST(CliFeasibility, RefinementBeyondTheInsertionBudgetIsRefusedBeforeRefining) {
  TempDir dir;
  const Timed t = run_default_with(dir, {{"max_circumradius", 1e-7}});
  expect_refused(dir, t, {"max circumradius 1e-07 m", "vertex insertions", "budget of 1e+07", "use a max_circumradius"});
}

TEST(CliFeasibility, AgentsBeyondHostMemoryAreRefused) {
  TempDir dir;
  const Timed t = run_default_with(dir, {{"agents", 2000000000}}, "--backend reference");
  expect_refused(dir, t, {"host memory", "available", "B per agent x 2e+09 agents", "use fewer agents"});
}

TEST(CliFeasibility, AgentsBeyondDeviceMemoryAreRefused) {
  TempDir dir;
  const Timed t = run_default_with(dir, {{"agents", 2000000000}}, "--backend opencl");
  if (t.result.err.find("no OpenCL") != std::string::npos) GTEST_SKIP() << t.result.err;
  expect_refused(dir, t, {"device memory", "B per agent on the device x 2e+09 agents"});
}

TEST(CliFeasibility, TimeStepBeyondTheModelsTimeScalesIsRefused) {
  TempDir dir;
  const Timed t = run_default_with(dir, {{"time_step", 1000}});
  expect_refused(dir, t, {"time_step 1000 s holds 20000 turn decisions", "more than the 4 per step",
                          "decay_rate * time_step = 1 /s * 1000 s = 1000"});
}

TEST(CliFeasibility, DecayWithinOneStepIsRefused) {
  TempDir dir;
  const Timed t = run_default_with(dir, {{"time_step", 0.5}, {"decay_rate", 1e6}});
  expect_refused(dir, t, {"decay_rate * time_step", "500000", "the field means nothing"});
}

TEST(CliFeasibility, LengthsBeyondATinySurfaceAreRefused) {
  TempDir dir;
  // 0.2 s: at the turn-decision limit, so the lengths are what is refused.
  const Timed t = run_default_with(dir, {{"scale_to_area", 1e-6}, {"time_step", 0.2}});
  expect_refused(dir, t, {"sensor_distance 0.05 m exceeds the surface's diameter", "move_rate * time_step = 0.1 m",
                          "agents wrap the surface every step"});
  TempDir dir2;
  expect_refused(dir2, run_default_with(dir2, {{"scale_to_area", 1e-6}, {"time_step", 0.5}}), {"turn decisions"});
}

TEST(CliFeasibility, SensorDistanceBeyondTheSurfaceIsRefused) {
  TempDir dir;
  expect_refused(dir, run_default_with(dir, {{"sensor_distance", 100}}),
                 {"sensor_distance 100 m exceeds the surface's diameter (bounding-box diagonal 1.9"});
  TempDir dir2;
  expect_refused(dir2, run_default_with(dir2, {{"time_step", 10}, {"sensor_distance", 100}}), {"turn decisions"});
}

TEST(CliFeasibility, ExplicitSubStepsBeyondTheLimitAreRefused) {
  TempDir dir;
  // Lengths that fit the tiny sphere, so the diffusion's sub-steps are what is refused.
  const Timed t = run_default_with(
      dir, {{"scale_to_area", 1e-6}, {"diffuse_rate", 10}, {"sensor_distance", 1e-5}, {"move_rate", 1e-3}});
  expect_refused(dir, t, {"forward Euler needs", "diffusion sub-steps per step", "integrator\": \"backward"});
  TempDir dir2;
  expect_refused(dir2, run_default_with(dir2, {{"scale_to_area", 1e-6}, {"decay_rate", 1e6}, {"diffuse_rate", 10}}),
                 {"decay_rate * time_step"});
}

TEST(CliFeasibility, LongTimeStepWarnsAndRuns) {
  TempDir dir;
  const Timed t = run_default_with(dir, {{"time_step", 0.1}}, "", 1);
  EXPECT_EQ(t.result.exit_code, 0) << t.result.err;
  EXPECT_NE(t.result.err.find("warning: time_step 0.1 s is longer than the turn-decision period"), std::string::npos)
      << t.result.err;
  // A short run with stderr not a terminal is not announced (the estimate is for someone waiting).
  EXPECT_EQ(t.result.err.find("physarum: estimate: "), std::string::npos) << t.result.err;
}

TEST(CliFeasibility, CompareRefusesTheSameScenes) {
  TempDir dir;
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/default.json"));
  scene["time_step"] = 1000;
  const std::filesystem::path path = dir.path / "scene.json";
  std::ofstream(path) << scene.dump(2);
  const auto start = std::chrono::steady_clock::now();
  const CommandResult r = testing::run_physarum("compare '" + path.string() + "' --seeds 2");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("turn decisions"), std::string::npos) << r.err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), kMaxSeconds);
}

// The refinement estimate is a lower bound of what refinement makes (so refusing on it never
// refuses a refinement that would fit) and announces the long ones (max_circumradius 0.001 on the
// default sphere: 38 s of refinement).
TEST(CliFeasibility, RefinementEstimateAnnouncesLongRefinements) {
  RefinementOptions options;
  options.max_circumradius = 0.001;
  const RefinementEstimate e = estimate_refinement(4.0, 642, options);
  EXPECT_GT(e.vertices, kRefinementNoteVertices);
  EXPECT_LT(e.vertices, 2.5e6);  // the refinement makes 2.49 million
  EXPECT_NE(e.describe().find("max circumradius 0.001 m"), std::string::npos) << e.describe();
}

}  // namespace
}  // namespace physarum
