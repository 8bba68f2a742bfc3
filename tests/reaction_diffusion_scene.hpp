#pragma once
// Reaction-diffusion scenes given as JSON in a test (the scene alone: loaded_scene.hpp's
// scene_from_json), and for the numerical tests its surface, evaluated maps and the built system.
#include "common/map_evaluation.hpp"
#include "common/reaction_diffusion_build.hpp"
#include "common/scene.hpp"
#include "common/scene_surface.hpp"
#include "loaded_scene.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace physarum::testing {

struct LoadedReactionDiffusion {
  Scene scene;
  SceneSurface surface;
  EvaluatedMaps maps;
  ReactionDiffusionSystem system;
};

inline LoadedReactionDiffusion load_rd_system(const nlohmann::json& j) {
  LoadedReactionDiffusion r;
  r.scene = scene_from_json(j);
  r.surface = prepare_scene_surface(r.scene);
  r.maps = evaluate_maps(r.scene.maps, r.surface, "test");
  r.system = build_reaction_diffusion_system(r.scene, r.surface, r.maps);
  return r;
}

}  // namespace physarum::testing
