// The differential harness as CI runs it: `physarum compare` on every comparison scene of
// tools/scenes/compare/, with the reference arm loaded from tests/reference_statistics/ (100
// reference seeds each, regenerated with --store-reference when the model changes), must find the
// OpenCL backend equivalent; and with each planted fault compiled into the kernels it must NOT.
//
// A harness that cannot fail proves nothing, so the fault cases are the point. Each fault is run on
// the scenes where it changes the model by more than the scene's margins (tools/scenes/compare/
// README.md has the table and the measured effects): no-reflect needs a boundary, no-decay-substep
// forward Euler, uniform-face unequal face areas and turnover, deposit-endpoint steps longer than
// the faces, turn-every-step a decision period of several steps.
//
// Runs are deterministic (fixed seeds, fixed-point deposits), so these tests do not flake: a given
// build and device always gives the same verdict. Only fault cases whose effect is well beyond the
// margin are required (another CPU's float rounding gives other seeds' trajectories, and a fault
// whose effect sits just above the margin could then pass by chance); the README's table lists the
// borderline rejections that are not tested.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace physarum::testing {
namespace {

std::string scene_path(const std::string& name) {
  return std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/compare/" + name + ".json";
}
std::string stats_path(const std::string& name) {
  return std::string(PHYSARUM_SOURCE_DIR) + "/tests/reference_statistics/" + name + ".json";
}

// spot.json needs the shared meshes.
bool scene_available(const std::string& name) { return name != "spot" || !shared_mesh_path("spot.obj").empty(); }

struct Verdict {
  CommandResult run;
  nlohmann::json json;
};

Verdict compare(const std::string& scene, const std::string& extra) {
  Verdict v;
  v.run = run_physarum("compare '" + scene_path(scene) + "' --reference-stats '" + stats_path(scene) + "' " + extra);
  try {
    v.json = nlohmann::json::parse(v.run.out);
  } catch (const nlohmann::json::exception&) {
    v.json = nlohmann::json();
  }
  return v;
}

// The metrics not judged equivalent, with their verdicts.
std::string failing_metrics(const nlohmann::json& verdict) {
  std::string names;
  if (!verdict.contains("metrics")) return names;
  for (const auto& m : verdict["metrics"])
    if (m["verdict"] != "equivalent") {
      names += ' ';
      names += m["name"].get<std::string>() + " (" + m["verdict"].get<std::string>() + ")";
    }
  return names;
}

class EquivalentScene : public ::testing::TestWithParam<std::string> {};

TEST_P(EquivalentScene, OpenCLIsEquivalentToTheReference) {
  const std::string scene = GetParam();
  if (!scene_available(scene)) GTEST_SKIP() << "shared/meshes/spot.obj is absent";
  TempDir out;
  const Verdict v = compare(scene, "--out '" + out.path.string() + "'");
  ASSERT_TRUE(v.json.is_object()) << v.run.err << v.run.out;
  EXPECT_EQ(v.run.exit_code, 0) << "failing metrics:" << failing_metrics(v.json) << "\n" << v.run.err;
  EXPECT_TRUE(v.json["equivalent"].get<bool>());
  EXPECT_FALSE(v.json["drift"]["drift"].get<bool>()) << "the stored reference statistics drifted";
  // The documented keys, and the outputs of --out.
  for (const char* key : {"equivalent", "seeds", "metrics"}) EXPECT_TRUE(v.json.contains(key)) << key;
  EXPECT_EQ(v.json["verdict"], "equivalent");
  EXPECT_EQ(v.json["seeds"]["reference"].get<int>(), 100);
  EXPECT_GE(v.json["seeds"]["opencl"].get<int>(), 8);
  for (const auto& m : v.json["metrics"])
    for (const char* key : {"name", "verdict", "reference_mean", "opencl_mean", "margin", "confidence_interval",
                            "p_value", "achieved_power", "pass"})
      EXPECT_TRUE(m.contains(key)) << key;
  for (const char* file : {"verdict.json", "seed_metrics.csv", "spectra.png", "fields.png"})
    EXPECT_TRUE(std::filesystem::exists(out.path / file)) << file;
  std::cout << scene << ": equivalent after " << v.json["seeds"]["opencl"] << " OpenCL seeds, "
            << v.json["sequential"]["looks"] << " looks\n";
}

INSTANTIATE_TEST_SUITE_P(CompareHarness, EquivalentScene,
                         ::testing::Values("square", "disk", "sphere", "torus", "spot"),
                         [](const auto& param_info) { return param_info.param; });

struct FaultCase {
  std::string fault, scene;
};

// Readable test names in ctest's listing instead of the struct's bytes.
void PrintTo(const FaultCase& c, std::ostream* os) { *os << c.fault << " on " << c.scene; }

class PlantedFault : public ::testing::TestWithParam<FaultCase> {};

TEST_P(PlantedFault, IsRejected) {
  const FaultCase c = GetParam();
  if (!scene_available(c.scene)) GTEST_SKIP() << "shared/meshes/spot.obj is absent";
  const Verdict v = compare(c.scene, "--fault " + c.fault + " --reference-seeds 2");
  ASSERT_TRUE(v.json.is_object()) << v.run.err << v.run.out;
  EXPECT_EQ(v.run.exit_code, 3) << c.fault << " on " << c.scene << " was judged " << v.json["verdict"];
  EXPECT_EQ(v.json["verdict"], "different");
  EXPECT_FALSE(v.json["equivalent"].get<bool>());
  EXPECT_EQ(v.json["fault"], c.fault);
  std::cout << c.fault << " on " << c.scene << ": rejected by" << failing_metrics(v.json) << "\n";
}

INSTANTIATE_TEST_SUITE_P(CompareHarness, PlantedFault,
                         ::testing::Values(FaultCase{"sensor-angle", "square"}, FaultCase{"sensor-angle", "torus"},
                                           FaultCase{"sensor-angle", "spot"},
                                           FaultCase{"deposit-endpoint", "disk"},
                                           FaultCase{"no-decay-substep", "square"},
                                           FaultCase{"no-decay-substep", "spot"},
                                           FaultCase{"no-reflect", "square"}, FaultCase{"no-reflect", "disk"},
                                           FaultCase{"uniform-face", "spot"}, FaultCase{"uniform-face", "torus"},
                                           FaultCase{"turn-every-step", "disk"},
                                           FaultCase{"turn-every-step", "torus"}),
                         [](const auto& param_info) {
                           std::string name = param_info.param.fault + "_on_" + param_info.param.scene;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

TEST(CompareHarness, UsageErrorsExitTwo) {
  EXPECT_EQ(run_physarum("compare '" + scene_path("square") + "' --fault no-such-fault").exit_code, 2);
  EXPECT_EQ(run_physarum("compare '" + scene_path("square") + "' --max-seeds 1").exit_code, 2);
  EXPECT_EQ(run_physarum("compare '" + scene_path("square") + "' --arm agents=100").exit_code, 2);
  EXPECT_EQ(run_physarum("compare '" + scene_path("square") + "' --arm agents --arm agents=100").exit_code, 2);
  EXPECT_EQ(run_physarum("compare").exit_code, 2);
}

TEST(CompareHarness, StoredStatisticsOfAnotherSceneAreRefused) {
  const CommandResult r = run_physarum("compare '" + scene_path("square") + "' --reference-stats '" +
                                       stats_path("disk") + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("other scene parameters"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

}  // namespace
}  // namespace physarum::testing
