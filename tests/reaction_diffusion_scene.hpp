#pragma once
// Reaction-diffusion scenes given as JSON in a test (the scene alone: the library's
// scene_from_json), and for the numerical tests its surface, evaluated maps and the built system.
#include "common/maps/map_evaluation.hpp"
#include "common/setup/reaction_diffusion_build.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"
#include "loaded_scene.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace physarum::testing {

struct LoadedReactionDiffusion {
  Scene scene;
  PreparedSurface surface;
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

// The intrinsic vertices' positions on the simulated (scaled) surface, from their barycentrics.
inline std::vector<Eigen::Vector3d> vertex_positions(const PreparedSurface& surface) {
  std::vector<Eigen::Vector3d> p;
  for (const SurfacePoint& s : surface.domain.vertex_location) {
    const auto& t = surface.simulated.triangles[static_cast<size_t>(s.face)];
    p.push_back(s.barycentric[0] * surface.simulated.positions[static_cast<size_t>(t[0])] +
                s.barycentric[1] * surface.simulated.positions[static_cast<size_t>(t[1])] +
                s.barycentric[2] * surface.simulated.positions[static_cast<size_t>(t[2])]);
  }
  return p;
}

}  // namespace physarum::testing
