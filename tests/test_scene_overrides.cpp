// Scene overrides with nested keys (common/scene/scene_overrides.hpp): the dotted-key rule reaches object
// members and list elements, creates missing objects, and refuses paths that do not exist; values
// parse as JSON or stay strings.
#include "common/base/errors.hpp"
#include "common/scene/scene.hpp"
#include "common/scene/scene_overrides.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace physarum {
namespace {

using nlohmann::json;

TEST(SceneOverrides, DottedKeysReachNestedMembersAndListElements) {
  json scene = json::parse(R"({"turn_rate": 180, "maps": {"ramp": {"axis": "y", "range": [0, 1]}},
                               "read_stimuli": [{"map": "ramp", "weight": 0.5}, {"map": "ramp", "weight": 1}]})");
  apply_scene_overrides(scene,
                        json::parse(R"({"turn_rate": 90, "maps.ramp.range": [0.5, 1.5], "read_stimuli.1.weight": -2,
                                        "maps.spot": {"axis": "x"}, "bias.strength": 40})"),
                        "s.json");
  EXPECT_EQ(scene["turn_rate"], 90);
  EXPECT_EQ(scene["maps"]["ramp"]["range"], json::parse("[0.5, 1.5]"));
  EXPECT_EQ(scene["maps"]["ramp"]["axis"], "y");  // siblings untouched
  EXPECT_EQ(scene["read_stimuli"][0]["weight"], 0.5);
  EXPECT_EQ(scene["read_stimuli"][1]["weight"], -2);
  EXPECT_EQ(scene["maps"]["spot"]["axis"], "x");   // a missing object is created
  EXPECT_EQ(scene["bias"]["strength"], 40);        // ... on the way too
}

TEST(SceneOverrides, PathsThatDoNotExistAreRefusedNamingTheKey) {
  json scene = json::parse(R"({"turn_rate": 180, "read_stimuli": [{"weight": 1}]})");
  for (const char* key : {"read_stimuli.1.weight", "read_stimuli.x.weight", "turn_rate.value", "maps..range"}) {
    json copy = scene;
    try {
      apply_scene_overrides(copy, json{{key, 1}}, "s.json");
      ADD_FAILURE() << key << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

TEST(SceneOverrides, AssignmentValuesAreJsonOrStrings) {
  EXPECT_EQ(parse_scene_assignment("turn_rate=90", "--set").second, 90);
  EXPECT_EQ(parse_scene_assignment("maps.r.range=[0.5,1.5]", "--set").second, json::parse("[0.5,1.5]"));
  EXPECT_EQ(parse_scene_assignment("mesh=shape:torus", "--set").second, "shape:torus");
  EXPECT_EQ(parse_scene_assignment(" seed = 7 ", "--set").first, "seed");
  EXPECT_THROW(parse_scene_assignment("turn_rate", "--set"), UsageError);
  EXPECT_THROW(parse_scene_assignment("=3", "--set"), UsageError);
}

TEST(SceneOverrides, LoadSceneAppliesNestedOverridesWithItsChecks) {
  testing::TempDir dir;
  const auto path = dir.path / "scene.json";
  std::ofstream(path) << R"({"mesh": "shape:sphere", "agents": 10, "time_step": 0.01,
    "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
    "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
    "mean_lifetime": 1.0, "activation_time": 0.2,
    "maps": {"east": {"direction": [1, 0, 0]}}, "bias": {"direction": "east", "strength": 10}})";
  const Scene s = load_scene(path.string(), json{{"bias.strength", 40.0}, {"agents", 25}});
  EXPECT_EQ(s.agent_model().agents, 25);
  ASSERT_TRUE(s.agent_model().controls.bias.has_value());
  EXPECT_EQ(std::get<double>(s.agent_model().controls.bias->strength), 40.0);
  // A nested override goes through the same validation: a negative agent count is refused.
  EXPECT_THROW(load_scene(path.string(), json{{"agents", -1}}), InputError);
  EXPECT_THROW(load_scene(path.string(), json{{"bias.no_such_key", 1}}), InputError);
}

}  // namespace
}  // namespace physarum
