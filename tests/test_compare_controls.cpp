// The differential harness on the controls of Sec. 3.3 (tools/scenes/compare/): scenes that use a
// parameter map with a directional bias, read- and write-stimuli, a sink with spawn weights and a
// terminating boundary, a per-vertex parameter map, and two competing species, each judged equivalent between the OpenCL
// backend and the reference at the harness's default settings (both arms run here; no stored
// statistics), and the planted faults of the controls each judged different on the scene where the
// control they break is strong:
//   bias-farthest-copy    maps_bias       (symmetry 2: the farthest copy is perpendicular)
//   stimulus-sign         stimuli         (a large disk attracting at 10 U: repelling empties it)
//   spawn-weights-ignored sink_spawn      (one half of the disk spawns five times the other)
//   map-at-centroid       activation_map  (activation time alternating 0 / 1.5 s from vertex to
//                                          vertex: the active fraction is convex in it, so the
//                                          centroid's mean value deposits less than interpolation)
//   species-matrix-transposed two_species (competing species, matrix [[1, -2], [0, 1]]: species 0
//                                          shuns species 1; transposed it ignores it, and the
//                                          harness measures species 0's layer)
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <iostream>
#include <ostream>
#include <string>

namespace physarum::testing {
namespace {

struct Verdict {
  CommandResult run;
  nlohmann::json json;
};

Verdict compare(const std::string& scene, const std::string& extra) {
  Verdict v;
  v.run = run_physarum("compare '" + std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/compare/" + scene + ".json' " + extra);
  try {
    v.json = nlohmann::json::parse(v.run.out);
  } catch (const nlohmann::json::exception&) {
    v.json = nlohmann::json();
  }
  return v;
}

class ControlScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ControlScene, OpenCLIsEquivalentToTheReference) {
  const Verdict v = compare(GetParam(), "");
  ASSERT_TRUE(v.json.is_object()) << v.run.err;
  EXPECT_EQ(v.run.exit_code, 0) << v.run.out;
  EXPECT_EQ(v.json["verdict"], "equivalent");
  std::cout << GetParam() << ": " << v.json["verdict"] << " after " << v.json["seeds"] << " seeds\n";
}

INSTANTIATE_TEST_SUITE_P(CompareControls, ControlScene,
                         ::testing::Values("maps_bias", "stimuli", "sink_spawn", "activation_map", "two_species"),
                         [](const auto& param_info) { return param_info.param; });

struct FaultCase {
  std::string fault, scene;
};

void PrintTo(const FaultCase& c, std::ostream* os) { *os << c.fault << " on " << c.scene; }

class ControlFault : public ::testing::TestWithParam<FaultCase> {};

TEST_P(ControlFault, IsJudgedDifferent) {
  const FaultCase c = GetParam();
  const Verdict v = compare(c.scene, "--fault " + c.fault);
  ASSERT_TRUE(v.json.is_object()) << v.run.err;
  EXPECT_EQ(v.run.exit_code, 3) << v.run.out;
  EXPECT_EQ(v.json["verdict"], "different");
  EXPECT_EQ(v.json["fault"], c.fault);
}

INSTANTIATE_TEST_SUITE_P(CompareControls, ControlFault,
                         ::testing::Values(FaultCase{"bias-farthest-copy", "maps_bias"},
                                           FaultCase{"stimulus-sign", "stimuli"},
                                           FaultCase{"spawn-weights-ignored", "sink_spawn"},
                                           FaultCase{"map-at-centroid", "activation_map"},
                                           FaultCase{"species-matrix-transposed", "two_species"}),
                         [](const auto& param_info) {
                           std::string name = param_info.param.fault + "_on_" + param_info.param.scene;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace physarum::testing
