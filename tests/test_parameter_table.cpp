// The parameter table (common/model/model_parameters.hpp) is the one description of the model's
// parameters: the scene keys, their checks, run.json's "parameters", the kernels' record and the
// table of keys in docs/scenes.md all follow from it. These tests fail when any of them drifts from it.
#include "common/base/errors.hpp"
#include "common/model/model_parameters.hpp"
#include "common/scene/scene.hpp"
#include "common/scene/scene_json.hpp"
#include "common/scene/scene_keys.hpp"
#include "opencl/agent_parameters.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace physarum {
namespace {

using nlohmann::json;
using testing::TempDir;

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// The table of scene keys in docs/scenes.md: the text between its two markers.
std::string readme_scene_keys(const std::string& readme) {
  const std::string begin = "<!-- scene-keys:", end = "<!-- end scene-keys -->";
  const auto b = readme.find(begin), e = readme.find(end);
  if (b == std::string::npos || e == std::string::npos) return {};
  const auto table = readme.find("| key |", b);
  return table < e ? readme.substr(table, e - table) : std::string();
}

// docs/scenes.md shows exactly the keys the parser takes, with their units, ranges and defaults: a key
// added to the table but not to docs/scenes.md (or the reverse, or a changed range) fails here.
TEST(ParameterTable, ReadmeTableIsTheGeneratedOne) {
  const std::string readme = read_file(std::filesystem::path(PHYSARUM_SOURCE_DIR) / "docs" / "scenes.md");
  const std::string shown = readme_scene_keys(readme);
  ASSERT_FALSE(shown.empty()) << "docs/scenes.md has no scene-keys block";
  EXPECT_EQ(shown, scene_keys_markdown()) << "regenerate it with ./build/physarum scene-keys";
  // The check itself can fail: a README without one row is caught.
  const std::string row = "| `diffuse_rate` |";
  std::string broken = shown;
  broken.erase(broken.find(row), broken.find('\n', broken.find(row)) - broken.find(row) + 1);
  EXPECT_NE(broken, scene_keys_markdown());
}

// Every key of every shipped scene is a described key: nothing reaches the parser that the table
// does not describe.
TEST(ParameterTable, EveryShippedSceneKeyIsDescribed) {
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(std::filesystem::path(PHYSARUM_SOURCE_DIR) /
                                                                          "tools" / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    const json scene = json::parse(read_file(entry.path()));
    for (auto it = scene.begin(); it != scene.end(); ++it)
      EXPECT_NE(find_scene_key(it.key()), nullptr) << entry.path() << ": key " << it.key();
  }
  EXPECT_GE(files, 9);
}

TEST(ParameterTable, RowsAreCompleteAndUnique) {
  std::set<std::string_view> keys, device_names;
  for (const ParameterSpec& p : kParameterTable) {
    EXPECT_TRUE(keys.insert(p.key).second) << p.key;
    EXPECT_FALSE(p.unit.empty()) << p.key;
    EXPECT_FALSE(p.doc.empty()) << p.key;
    EXPECT_GT(p.file_to_si, 0.0) << p.key;
    const SceneKey* k = find_scene_key(p.key);
    ASSERT_NE(k, nullptr) << p.key;
    EXPECT_EQ(k->parameter, p.id);
    if (p.user == ParamUser::Agent) {
      EXPECT_TRUE(device_names.insert(p.device_name).second) << p.key;
    }
    if (p.default_value) {
      EXPECT_TRUE(p.range.contains(*p.default_value)) << p.key;
    }
  }
  EXPECT_EQ(keys.size(), kParamCount);
  EXPECT_EQ(device_names.size(), kAgentParamCount);
  // Settings keys do not shadow parameters.
  std::set<std::string_view> all;
  for (const SceneKey& k : scene_keys()) EXPECT_TRUE(all.insert(k.name).second) << k.name;
}

// Parsing follows the table: a required parameter that is missing, and any value outside a row's
// range, are refused with the key, the value and the range; an optional one takes its default.
TEST(ParameterTable, ParsingFollowsTheTable) {
  const json valid = json::parse(R"({
    "mesh": "shape:sphere", "agents": 10, "time_step": 0.01, "sensor_distance": 0.05, "sensor_angle": 22.5,
    "move_rate": 0.5, "turn_rate": 180.0, "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0,
    "diffuse_rate": 0.0002, "mean_lifetime": 1.0, "activation_time": 0.2})");
  TempDir dir;
  const auto load = [&](const json& j) {
    const std::string path = (dir.path / "scene.json").string();
    std::ofstream(path) << j.dump();
    return load_scene(path);
  };
  for (const ParameterSpec& p : kParameterTable) {
    json missing = valid;
    missing.erase(std::string(p.key));
    if (p.default_value) {
      EXPECT_EQ(load(missing).agent_model().parameters[p.id], *p.default_value * p.file_to_si) << p.key;
    } else {
      try {
        load(missing);
        ADD_FAILURE() << p.key << ": a missing required key was accepted";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("'" + std::string(p.key) + "'"), std::string::npos) << e.what();
      }
    }
    // Just outside the range, on the side that has a finite bound.
    const double outside = std::isfinite(p.range.low) ? p.range.low - 1.0 : p.range.high + 1.0;
    json bad = valid;
    bad[std::string(p.key)] = outside;
    try {
      load(bad);
      ADD_FAILURE() << p.key << " = " << outside << " was accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("'" + std::string(p.key) + "'"), std::string::npos) << message;
      EXPECT_NE(message.find(p.range.describe()), std::string::npos) << message;
    }
  }
}

// run.json's "parameters" name every row, in the file's units, and read back as the same scene.
TEST(ParameterTable, RunJsonParametersRoundTrip) {
  Scene scene;
  scene.mesh = "shape:sphere";
  scene.agent_model().agents = 5;
  scene.time_step = 0.02;
  double value = 0.25;
  for (const ParameterSpec& p : kParameterTable) scene.agent_model().parameters[p.id] = (value += 0.125) * p.file_to_si;
  scene.agent_model().parameters[Param::mean_lifetime] = std::numeric_limits<double>::infinity();
  const nlohmann::ordered_json j = scene_parameters_json(scene);
  for (const ParameterSpec& p : kParameterTable) ASSERT_TRUE(j.contains(std::string(p.key))) << p.key;
  EXPECT_TRUE(j["mean_lifetime"].is_null());
  TempDir dir;
  const std::string path = (dir.path / "again.json").string();
  std::ofstream(path) << j.dump();
  const Scene again = load_scene(path);
  for (const ParameterSpec& p : kParameterTable) {
    if (p.id == Param::mean_lifetime) continue;  // +infinity, checked below
    EXPECT_NEAR(again.agent_model().parameters[p.id], scene.agent_model().parameters[p.id], 1e-12 * std::abs(scene.agent_model().parameters[p.id])) << p.key;
  }
  EXPECT_TRUE(std::isinf(again.agent_model().parameters[Param::mean_lifetime]));
}

// The kernels' record has one named float per agent parameter, in table order, and the host packs
// each parameter's device form into that slot.
TEST(ParameterTable, KernelRecordFollowsTheTable) {
  const std::string header = opencl::agent_parameters_header();
  size_t at = 0;
  for (const Param p : kAgentParams) {
    const std::string field = "float " + std::string(parameter_spec(p).device_name) + ";";
    const size_t found = header.find(field, at);
    ASSERT_NE(found, std::string::npos) << field << " missing or out of table order";
    at = found;
  }
  ParameterValues values;
  double v = 1.0;
  for (const ParameterSpec& p : kParameterTable) values[p.id] = (v *= 2.0);
  const opencl::PackedAgentParameters packed = opencl::pack_agent_parameters(VertexParameters::constant(values, 3));
  ASSERT_EQ(packed.per_vertex.size(), 3u);
  EXPECT_TRUE(packed.uniform);
  for (size_t slot = 0; slot < kAgentParamCount; ++slot) {
    const ParameterSpec& spec = parameter_spec(kAgentParams[slot]);
    EXPECT_EQ(packed.per_vertex[2].value[slot], static_cast<float>(device_value(spec, values[spec.id]))) << spec.key;
  }
  EXPECT_EQ(device_value(parameter_spec(Param::mean_lifetime), 4.0), 0.25);  // a hazard rate
  EXPECT_EQ(device_value(parameter_spec(Param::mean_lifetime), std::numeric_limits<double>::infinity()), 0.0);
}

}  // namespace
}  // namespace physarum
