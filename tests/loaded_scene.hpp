#pragma once
// A scene given as JSON in a test, loaded as `physarum run` loads a file: the scene, its surface and
// the arrays (parameters, controls, species) the backends are built from.
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/setup/scene_surface.hpp"
#include "test_support.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>

namespace physarum::testing {

struct LoadedScene {
  Scene scene;
  PreparedSurface surface;
  SceneArrays arrays;
};

inline LoadedScene load_scene_json(const nlohmann::json& j) {
  Scene scene = physarum::scene_from_json(j);  // the library's reader: the file's checks and defaults
  PreparedSurface surface = prepare_scene_surface(scene);
  SceneArrays arrays = scene_arrays(scene, surface);
  return LoadedScene{std::move(scene), std::move(surface), std::move(arrays)};
}

}  // namespace physarum::testing
