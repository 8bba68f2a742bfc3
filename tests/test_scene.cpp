// Scene files (the README's "Scene files"): every key, every bad value named with its value and the
// allowed range, unknown keys with a suggestion, JSON errors with line and column.
#include "common/setup/agent_inputs.hpp"
#include "common/scene/scene.hpp"

#include "common/scene/default_scene.hpp"
#include "common/base/errors.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/model/vertex_parameters.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <numbers>

namespace physarum {
namespace {

using nlohmann::json;
using testing::TempDir;

json valid_scene() {
  return json::parse(R"({
    "mesh": "shape:sphere", "scale_to_area": 4.0, "max_circumradius": 0.02, "agents": 100000,
    "time_step": 0.01, "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5,
    "turn_rate": 180.0, "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0,
    "diffuse_rate": 0.0002, "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward", "seed": 1
  })");
}

std::string write(const TempDir& dir, const std::string& text, const std::string& name = "scene.json") {
  const std::string path = (dir.path / name).string();
  std::ofstream(path) << text;
  return path;
}

// The InputError message of loading `scene`, or "" when it loads.
std::string load_error(const json& scene) {
  TempDir dir;
  const std::string path = write(dir, scene.dump(2));
  try {
    load_scene(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, LoadsTheDesignExampleWithUnitsConverted) {
  TempDir dir;
  const Scene s = load_scene(write(dir, valid_scene().dump()));
  EXPECT_EQ(s.mesh, "shape:sphere");
  EXPECT_EQ(s.agent_model().agents, 100000);
  EXPECT_DOUBLE_EQ(*s.scale_to_area, 4.0);
  EXPECT_DOUBLE_EQ(*s.max_circumradius, 0.02);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::sensor_angle], 22.5 * std::numbers::pi / 180.0);  // degrees in the file
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::turn_rate], std::numbers::pi);                    // 180 deg/s
  EXPECT_DOUBLE_EQ(s.time_step, 0.01);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::sensor_distance], 0.05);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::move_rate], 0.5);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::turn_frequency], 20.0);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::deposit_rate], 1.0);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::decay_rate], 1.0);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::diffuse_rate], 0.0002);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::mean_lifetime], 1.0);
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::activation_time], 0.2);
  EXPECT_EQ(s.agent_model().integrator, Integrator::Forward);
  EXPECT_EQ(s.seed, 1u);
  EXPECT_FALSE(s.steps.has_value());
  EXPECT_FALSE(s.sim_time.has_value());
}

TEST(Scene, OptionalKeysAndNullLifetime) {
  json j = valid_scene();
  j["mean_lifetime"] = nullptr;
  j["integrator"] = "backward";
  j["min_angle"] = 25;
  j["steps"] = 300;
  j["seed"] = 4294967295u;
  j.erase("scale_to_area");
  j.erase("max_circumradius");
  j.erase("activation_time");
  TempDir dir;
  const Scene s = load_scene(write(dir, j.dump()));
  EXPECT_TRUE(std::isinf(s.agent_model().parameters[Param::mean_lifetime]));  // null: no turnover
  EXPECT_EQ(s.agent_model().integrator, Integrator::Backward);
  EXPECT_DOUBLE_EQ(s.min_angle_deg, 25.0);
  EXPECT_EQ(*s.steps, 300);
  EXPECT_EQ(s.seed, 4294967295u);
  EXPECT_FALSE(s.scale_to_area.has_value());
  EXPECT_DOUBLE_EQ(s.agent_model().parameters[Param::activation_time], 0.0);
  // No turnover: every agent deposits eventually, so U has no exp(-t_a / tau) factor.
  EXPECT_DOUBLE_EQ(uniform_steady_state(s, 2.0), 100000 * 1.0 / (1.0 * 2.0));
}

// One bad value per key: the message names the key, repeats the value and states the range.
TEST(Scene, EveryOutOfRangeValueIsNamedWithItsRange) {
  struct Case {
    const char* key;
    json value;
    const char* range;
  };
  const Case cases[] = {
      {"scale_to_area", 0.0, "must be > 0"},          {"max_circumradius", -0.5, "must be > 0"},
      {"min_angle", 45, "must be in [0, 30]"},         {"agents", 0, "must be in [1, 2147483647]"},
      {"time_step", 0, "must be > 0"},                 {"sensor_distance", -1, "must be > 0"},
      {"sensor_angle", 200, "must be in [-180, 180]"}, {"move_rate", -0.1, "must be >= 0"},
      {"turn_rate", -5, "must be >= 0"},               {"turn_frequency", 0, "must be > 0"},
      {"deposit_rate", -1, "must be >= 0"},            {"decay_rate", 0, "must be > 0"},
      {"diffuse_rate", -1e-3, "must be >= 0"},         {"mean_lifetime", -2, "must be > 0"},
      {"activation_time", -0.2, "must be >= 0"},       {"seed", -1, "must be in [0, 4294967295]"},
      {"steps", 0, "must be in [1, 1e+15]"},                      {"sim_time", -3, "must be > 0"},
  };
  for (const Case& c : cases) {
    json j = valid_scene();
    j[c.key] = c.value;
    const std::string message = load_error(j);
    SCOPED_TRACE(message);
    EXPECT_NE(message.find("scene.json"), std::string::npos) << c.key;
    EXPECT_NE(message.find(std::string("key '") + c.key + "' = " + c.value.dump()), std::string::npos) << c.key;
    EXPECT_NE(message.find(std::string("out of range (") + c.range), std::string::npos) << c.key;
  }
}

TEST(Scene, WrongTypesAreNamed) {
  for (const char* key : {"agents", "time_step", "seed"}) {
    json j = valid_scene();
    j[key] = "fast";
    const std::string message = load_error(j);
    EXPECT_NE(message.find(std::string("key '") + key + "' = \"fast\" has the wrong type (string"), std::string::npos)
        << message;
  }
  // A model parameter's text is a map name (parameter maps, Sec. 3.3): without such a map the
  // message shows the value and says so.
  for (const char* key : {"sensor_angle", "decay_rate", "mean_lifetime"}) {
    json j = valid_scene();
    j[key] = "fast";
    const std::string message = load_error(j);
    EXPECT_NE(message.find(std::string("key '") + key + "' = \"fast\": map 'fast' is not defined in 'maps'"),
              std::string::npos)
        << message;
  }
  json j = valid_scene();
  j["mesh"] = 3;
  EXPECT_NE(load_error(j).find("key 'mesh' = 3 has the wrong type"), std::string::npos);
  j = valid_scene();
  j["agents"] = 2.5;
  EXPECT_NE(load_error(j).find("key 'agents' = 2.5 must be a whole number"), std::string::npos);
  j = valid_scene();
  j["agents"] = 1e5;  // a float with an integral value is a fine integer
  EXPECT_EQ(load_error(j), "");
  j = valid_scene();
  j["integrator"] = "rk4";
  EXPECT_NE(load_error(j).find("key 'integrator' = \"rk4\" is out of range (must be \"forward\" or \"backward\")"),
            std::string::npos);
  j = valid_scene();
  j["decay_rate"] = nullptr;  // null is only allowed for mean_lifetime
  EXPECT_NE(load_error(j).find("key 'decay_rate' = null has the wrong type"), std::string::npos) << load_error(j);
}

TEST(Scene, UnknownKeyIsRejectedWithSuggestion) {
  json j = valid_scene();
  j["sensor_distanse"] = 0.05;
  const std::string message = load_error(j);
  EXPECT_NE(message.find("unknown key 'sensor_distanse'"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'sensor_distance'"), std::string::npos) << message;
  j = valid_scene();
  j["decay"] = 1.0;
  EXPECT_NE(load_error(j).find("did you mean 'decay_rate'"), std::string::npos) << load_error(j);
}

TEST(Scene, MissingRequiredKeysAreNamed) {
  for (const char* key : {"mesh", "agents", "time_step", "sensor_distance", "sensor_angle", "move_rate", "turn_rate",
                          "turn_frequency", "deposit_rate", "decay_rate", "diffuse_rate", "mean_lifetime"}) {
    json j = valid_scene();
    j.erase(key);
    EXPECT_NE(load_error(j).find(std::string("required key '") + key + "' is missing"), std::string::npos) << key;
  }
}

TEST(Scene, MalformedJsonReportsLineAndColumn) {
  TempDir dir;
  const std::string path = write(dir, "{\n  \"mesh\": \"shape:sphere\",\n  \"agents\": 10,,\n}\n");
  try {
    load_scene(path);
    FAIL() << "malformed JSON was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
    EXPECT_NE(message.find("column"), std::string::npos) << message;
  }
  EXPECT_THROW(load_scene(write(dir, "[1, 2]", "array.json")), InputError);
  EXPECT_THROW(load_scene((dir.path / "absent.json").string()), InputError);
}

TEST(Scene, DuplicateKeyAndConflictingRunLengthsAreErrors) {
  TempDir dir;
  std::string text = valid_scene().dump();
  text.insert(text.size() - 1, ", \"agents\": 5");
  try {
    load_scene(write(dir, text));
    FAIL() << "duplicate key accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'agents' appears more than once"), std::string::npos) << e.what();
  }
  json j = valid_scene();
  j["steps"] = 10;
  j["sim_time"] = 1.0;
  EXPECT_NE(load_error(j).find("'steps' and 'sim_time' are both given"), std::string::npos);
}

TEST(Scene, RelativeMeshPathIsResolvedAgainstTheSceneFolder) {
  TempDir dir;
  std::filesystem::create_directories(dir.path / "scenes" / "meshes");
  std::ofstream(dir.path / "scenes" / "meshes" / "m.obj") << "v 0 0 0\n";
  json j = valid_scene();
  j["mesh"] = "meshes/m.obj";
  const Scene s = load_scene(write(dir, j.dump(), "scenes/a.json"));
  EXPECT_TRUE(std::filesystem::equivalent(s.mesh, dir.path / "scenes" / "meshes" / "m.obj")) << s.mesh;
  j["mesh"] = "meshes/none.obj";
  try {
    load_scene(write(dir, j.dump(), "scenes/b.json"));
    FAIL() << "missing mesh file accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'mesh' = \"meshes/none.obj\": file not found"), std::string::npos)
        << e.what();
  }
}

TEST(Scene, ValidateSceneChecksSceneBuiltInCode) {
  TempDir dir;
  Scene s = load_scene(write(dir, valid_scene().dump()));
  EXPECT_NO_THROW(validate_scene(s));
  s.agent_model().parameters[Param::sensor_angle] = 4.0;  // radians: 229 degrees
  try {
    validate_scene(s);
    FAIL() << "sensor angle of 229 degrees accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'sensor_angle' = 229.18"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("must be in [-180, 180]"), std::string::npos) << e.what();
  }
  s = Scene{};
  s.mesh = "shape:square";
  EXPECT_THROW(validate_scene(s), InputError);  // all rates zero: time_step is the first to fail
}

TEST(Scene, VertexParametersAreConstantPerVertex) {
  TempDir dir;
  json j = valid_scene();
  j["mean_lifetime"] = nullptr;
  const Scene s = load_scene(write(dir, j.dump()));
  const VertexParameters p = VertexParameters::constant(s.agent_model().parameters, 7);
  EXPECT_EQ(p.vertex_count(), 7);
  for (const ParameterSpec& spec : kParameterTable) {
    EXPECT_EQ(p[spec.id].size(), 7u) << spec.key;
    EXPECT_TRUE(is_uniform(p[spec.id])) << spec.key;
  }
  EXPECT_DOUBLE_EQ(p[Param::sensor_angle][3], s.agent_model().parameters[Param::sensor_angle]);
  EXPECT_DOUBLE_EQ(p[Param::diffuse_rate][6], 0.0002);
  EXPECT_TRUE(std::isinf(p[Param::mean_lifetime][0]));  // no turnover: zero hazard
  EXPECT_FALSE(is_uniform(IntrinsicVertexData<double>(std::vector<double>{1.0, 1.0, 2.0})));
}

// The parameters code builds without a file (benchmarks, tests) are the shipped default scene's,
// bit for bit, as load_scene converts them.
TEST(Scene, DefaultSceneParametersAreTheShippedDefaultScene) {
  const Scene file = load_scene(std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/default.json");
  const Scene code = default_scene_parameters(file.agent_model().agents);
  EXPECT_EQ(code.agent_model().agents, file.agent_model().agents);
  EXPECT_EQ(code.time_step, file.time_step);
  for (const ParameterSpec& spec : kParameterTable)
    EXPECT_EQ(code.agent_model().parameters[spec.id], file.agent_model().parameters[spec.id]) << spec.key;
  EXPECT_EQ(code.agent_model().integrator, file.agent_model().integrator);
  EXPECT_EQ(code.seed, file.seed);
}

}  // namespace
}  // namespace physarum
