// Competing species in a scene file ("species", "sensing"; common/scene/scene_species.hpp) and as the
// arrays a backend reads (common/model/species.hpp): each species takes the top-level parameters with its
// own overrides (numbers or maps, checked like the top-level keys), the agents add up, the sensing
// matrix defaults to the identity, and every bad entry is refused naming "species[i].KEY" or
// "sensing".
#include "common/base/errors.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/model/species.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <limits>

namespace physarum {
namespace {

using nlohmann::json;
using testing::TempDir;

json base_scene() {
  return {{"mesh", "shape:square"},  {"time_step", 0.02},      {"sensor_distance", 0.05},
          {"sensor_angle", 22.5},    {"move_rate", 0.5},       {"turn_rate", 180.0},
          {"turn_frequency", 20.0},  {"deposit_rate", 1.0},    {"decay_rate", 1.0},
          {"diffuse_rate", 0.0002},  {"mean_lifetime", 1.0}};
}

std::string write_scene(const TempDir& dir, const json& scene) {
  const std::string path = (dir.path / "scene.json").string();
  std::ofstream(path) << scene.dump(2);
  return path;
}

SceneArrays arrays_of(const json& j, Scene* loaded = nullptr) {
  TempDir dir;
  const Scene scene = load_scene(write_scene(dir, j));
  if (loaded) *loaded = scene;
  return scene_arrays(scene, prepare_scene_surface(scene));
}

std::string scene_error(const json& j) {
  return testing::input_error_of([&] { arrays_of(j); });
}

TEST(SpeciesScene, WithoutSpeciesTheSetIsOneSpeciesReadingItsOwnLayer) {
  json j = base_scene();
  j["agents"] = 300;
  const SceneArrays arrays = arrays_of(j);
  ASSERT_EQ(arrays.species.count(), 1);
  EXPECT_TRUE(arrays.species.is_single());
  EXPECT_EQ(arrays.species.species[0].agents, 300);
  for (const ParameterSpec& p : kParameterTable)
    EXPECT_EQ(arrays.species.species[0].parameters[p.id], arrays.parameters[p.id]) << p.key;
}

TEST(SpeciesScene, EachSpeciesOverridesOnlyWhatItGivesAndTheAgentsAddUp) {
  json j = base_scene();
  j["maps"] = {{"ramp_x", {{"axis", "x"}}}};
  j["species"] = {{{"agents", 100}, {"decay_rate", 2.0}, {"sensor_angle", 45.0}},
                  {{"agents", 50}, {"sensor_distance", {{"map", "ramp_x"}, {"range", {0.02, 0.06}}}}, {"mean_lifetime", nullptr}}};
  Scene scene;
  const SceneArrays arrays = arrays_of(j, &scene);
  EXPECT_EQ(scene.agent_model().agents, 150);  // the top-level count left out: the sum
  const SpeciesSet& set = arrays.species;
  ASSERT_EQ(set.count(), 2);
  EXPECT_EQ(set.species[0].agents, 100);
  EXPECT_EQ(set.species[1].agents, 50);
  // The identity by default: each species reads only its own layer.
  EXPECT_EQ(set.sensing, (std::vector<double>{1.0, 0.0, 0.0, 1.0}));
  const int n = set.species[0].parameters.vertex_count();
  for (int v = 0; v < n; ++v) {
    EXPECT_EQ(set.species[0].parameters[Param::decay_rate][v], 2.0);
    EXPECT_DOUBLE_EQ(set.species[0].parameters[Param::sensor_angle][v], 45.0 * kDegree);  // degrees -> radians
    EXPECT_EQ(set.species[0].parameters[Param::sensor_distance][v], 0.05);                 // inherited
    EXPECT_EQ(set.species[1].parameters[Param::decay_rate][v], 1.0);                       // inherited
    EXPECT_EQ(set.species[1].parameters[Param::mean_lifetime][v], std::numeric_limits<double>::infinity());
  }
  // The mapped override is the ramp remapped to 0.02 .. 0.06: its extremes on the square's corners.
  double lo = 1.0, hi = 0.0;
  for (double d : set.species[1].parameters[Param::sensor_distance]) lo = std::min(lo, d), hi = std::max(hi, d);
  EXPECT_NEAR(lo, 0.02, 1e-12);
  EXPECT_NEAR(hi, 0.06, 1e-12);
  EXPECT_EQ(set.species_of_agent(0), 0);
  EXPECT_EQ(set.species_of_agent(99), 0);
  EXPECT_EQ(set.species_of_agent(100), 1);
  EXPECT_EQ(set.species_of_agent(149), 1);
  EXPECT_EQ(set.first_agent(1), 100);
}

TEST(SpeciesScene, AGivenMatrixIsKeptRowByRow) {
  json j = base_scene();
  j["species"] = {{{"agents", 10}}, {{"agents", 20}}};
  j["sensing"] = {{1.0, -0.5}, {0.25, 2.0}};
  j["agents"] = 30;  // given and equal to the sum: accepted
  const SpeciesSet set = arrays_of(j).species;
  EXPECT_EQ(set.sensing_weight(0, 1), -0.5);  // row 0 = what species 0 reads
  EXPECT_EQ(set.sensing_weight(1, 0), 0.25);
  EXPECT_EQ(set.sensing_weight(1, 1), 2.0);
}

TEST(SpeciesScene, BadEntriesAreRefusedNamingTheirKey) {
  const auto with = [](json species, json sensing = nullptr, json agents = nullptr) {
    json j = base_scene();
    j["maps"] = {{"east", {{"direction", {1.0, 0.0, 0.0}}}}, {"two", 2.0}, {"minus", -1.0}};
    j["species"] = std::move(species);
    if (!sensing.is_null()) j["sensing"] = std::move(sensing);
    if (!agents.is_null()) j["agents"] = std::move(agents);
    return scene_error(j);
  };
  const json two = {{{"agents", 10}}, {{"agents", 20}}};
  EXPECT_NE(with(json::array()).find("'species'"), std::string::npos);
  EXPECT_NE(with({{{"agents", 10}, {"decay_rat", 1.0}}}).find("'species[0].decay_rat'"), std::string::npos);
  EXPECT_NE(with({{{"agents", 10}}, {{"decay_rate", 1.0}}}).find("'species[1]': missing \"agents\""), std::string::npos);
  EXPECT_NE(with({{{"agents", 2.5}}}).find("'species[0].agents'"), std::string::npos);
  EXPECT_NE(with({{{"agents", 0}}}).find("'species[0].agents'"), std::string::npos);
  EXPECT_NE(with({{{"agents", 10}}, {{"agents", 5}, {"decay_rate", 0.0}}}).find("'species[1].decay_rate' = 0"), std::string::npos);
  EXPECT_NE(with({{{"agents", 10}, {"turn_rate", "fast"}}}).find("'species[0].turn_rate'"), std::string::npos);
  EXPECT_NE(with({{{"agents", 10}, {"move_rate", "east"}}}).find("'species[0].move_rate'"), std::string::npos);  // a vector map
  // A map whose values leave the range is refused where it is evaluated, naming the species' key.
  EXPECT_NE(with({{{"agents", 10}, {"decay_rate", "minus"}}}).find("'species[0].decay_rate': map 'minus' gives -1"),
            std::string::npos);
  EXPECT_NE(with({{{"agents", 10}, {"decay_rate", {{"map", "two"}, {"range", {-1.0, 1.0}}}}}}).find("'species[0].decay_rate'"),
            std::string::npos);
  EXPECT_NE(with(two, json{{1.0, 0.0}}).find("'sensing'"), std::string::npos);
  EXPECT_NE(with(two, json{{1.0, 0.0}, {0.0}}).find("'sensing': row 1"), std::string::npos);
  EXPECT_NE(with(two, json{{1.0, "x"}, {0.0, 1.0}}).find("'sensing': [0][1]"), std::string::npos);
  EXPECT_NE(with(two, nullptr, 31).find("'agents': 31 differs from the sum"), std::string::npos);
  // "sensing" alone has nothing to act between.
  json j = base_scene();
  j["agents"] = 10;
  j["sensing"] = {{1.0}};
  EXPECT_NE(scene_error(j).find("'sensing'"), std::string::npos);
  // Each of these is valid once repaired: the messages above are about the entry, not the scene.
  EXPECT_EQ(with(two, json{{1.0, 0.0}, {0.0, 1.0}}), "");
}

}  // namespace
}  // namespace physarum
