// The library's way in (api/session.hpp) on both models: what a Session reads back is what its
// backend holds, on the input mesh it is exactly the input vertices' intrinsic values, a saved and
// restored session continues bit for bit as an uninterrupted one, and a checkpoint of another scene
// is refused. Also: a scene built from JSON in code is the scene load_scene reads from a file.
#include "api/session.hpp"
#include "common/base/errors.hpp"
#include "common/scene/scene.hpp"
#include "common/scene/scene_json.hpp"
#include "session_scenes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

namespace physarum {
namespace {

using nlohmann::json;
using testing::TempDir;

using testing::agent_scene_json;
using testing::reaction_scene_json;

SessionOptions quiet_reference() {
  SessionOptions o;
  o.backend = "reference";
  o.use_map_cache = false;
  return o;
}

TEST(Session, SceneFromJsonIsTheSceneLoadSceneReads) {
  TempDir dir;
  const std::string path = (dir.path / "scene.json").string();
  std::ofstream(path) << agent_scene_json().dump();
  const Scene from_file = load_scene(path);
  const Scene from_code = scene_from_json(agent_scene_json());
  EXPECT_EQ(scene_parameters_json(from_code).dump(), scene_parameters_json(from_file).dump());
  EXPECT_EQ(from_code.source, "");
  // The same checks: an unknown key names itself and the scene ("scene" when built in code).
  json bad = agent_scene_json();
  bad["sensor_distanse"] = 0.05;
  const std::string message = testing::input_error_of([&] { scene_from_json(bad); });
  EXPECT_NE(message.find("scene: unknown key 'sensor_distanse'"), std::string::npos) << message;
}

TEST(Session, FieldsOnTheInputMeshAreTheInputVerticesIntrinsicValues) {
  for (const json& j : {agent_scene_json(), reaction_scene_json()}) {
    Session session(scene_from_json(j), quiet_reference());
    session.step(5);
    EXPECT_EQ(session.steps_taken(), 5);
    ASSERT_EQ(static_cast<int>(session.layer_names().size()), session.backend().dynamic_layer_count());
    for (int layer = 0; layer < session.backend().dynamic_layer_count(); ++layer) {
      const IntrinsicVertexData<double> intrinsic = session.field(layer);
      const InputVertexData<double> input = session.field_on_input(layer);
      ASSERT_EQ(static_cast<int>(input.size()), session.surface().input.vertex_count());
      // Refinement appends vertices after the input's (common/surface/field_transfer.hpp).
      ASSERT_GT(intrinsic.size(), input.size());
      for (size_t v = 0; v < input.size(); ++v) ASSERT_EQ(input[v], intrinsic[v]) << j["mesh"] << " layer " << layer;
    }
  }
}

TEST(Session, NamesEachModelsLayers) {
  EXPECT_EQ(Session(scene_from_json(agent_scene_json()), quiet_reference()).layer_names(),
            std::vector<std::string>{"pheromone"});
  const Session rd(scene_from_json(reaction_scene_json()), quiet_reference());
  EXPECT_EQ(rd.layer_names(), (std::vector<std::string>{"u", "v"}));
  EXPECT_EQ(rd.preview_layer(), 1);  // gray-scott shows v by default
  EXPECT_EQ(rd.agent_arrays(), nullptr);
}

TEST(Session, SavedAndRestoredContinuesBitForBit) {
  TempDir dir;
  const std::string checkpoint = (dir.path / "state.bin").string();
  for (const json& j : {agent_scene_json(), reaction_scene_json()}) {
    Session straight(scene_from_json(j), quiet_reference());
    straight.step(12);

    Session first(scene_from_json(j), quiet_reference());
    first.step(7);
    first.save(checkpoint);
    Session resumed(scene_from_json(j), quiet_reference());
    resumed.restore(checkpoint);
    EXPECT_EQ(resumed.steps_taken(), 7);
    resumed.step(5);
    for (int layer = 0; layer < straight.backend().dynamic_layer_count(); ++layer)
      EXPECT_EQ(resumed.field(layer), straight.field(layer)) << j["model"] << " layer " << layer;
    EXPECT_EQ(resumed.time(), straight.time());
  }
}

TEST(Session, RestoreRefusesAnotherScenesCheckpoint) {
  TempDir dir;
  const std::string checkpoint = (dir.path / "state.bin").string();
  Session saved(scene_from_json(agent_scene_json()), quiet_reference());
  saved.step(2);
  saved.save(checkpoint);
  json other = agent_scene_json();
  other["decay_rate"] = 2.0;
  Session different(scene_from_json(other), quiet_reference());
  const std::string message = testing::input_error_of([&] { different.restore(checkpoint); });
  EXPECT_NE(message.find("scene"), std::string::npos) << message;
  EXPECT_EQ(different.steps_taken(), 0) << "a refused checkpoint changes nothing";
}

}  // namespace
}  // namespace physarum
