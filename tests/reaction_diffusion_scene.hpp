#pragma once
// Reaction-diffusion scenes given as JSON in a test, loaded as `physarum run` loads a file: the scene,
// and (for the numerical tests) its surface, evaluated maps and the built system.
#include "common/map_evaluation.hpp"
#include "common/reaction_diffusion_build.hpp"
#include "common/scene.hpp"
#include "common/scene_surface.hpp"
#include "test_support.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

namespace physarum::testing {

inline Scene load_rd_scene(const nlohmann::json& j) {
  TempDir dir;
  const std::string path = (dir.path / "scene.json").string();
  std::ofstream(path) << j.dump(2);
  return load_scene(path);
}

struct LoadedReactionDiffusion {
  Scene scene;
  SceneSurface surface;
  EvaluatedMaps maps;
  ReactionDiffusionSystem system;
};

inline LoadedReactionDiffusion load_rd_system(const nlohmann::json& j) {
  LoadedReactionDiffusion r;
  r.scene = load_rd_scene(j);
  r.surface = prepare_scene_surface(r.scene);
  r.maps = evaluate_maps(r.scene.maps, r.surface, "test");
  r.system = build_reaction_diffusion_system(r.scene, r.surface, r.maps);
  return r;
}

}  // namespace physarum::testing
