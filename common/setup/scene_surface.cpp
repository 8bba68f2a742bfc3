#include "common/setup/scene_surface.hpp"

namespace physarum {

SurfaceSpec surface_spec(const Scene& scene) {
  return SurfaceSpec{scene.mesh, scene.scale_to_area, scene.max_circumradius, scene.min_angle_deg};
}

PreparedSurface prepare_scene_surface(const Scene& scene, const SurfaceNote& note) {
  return prepare_surface(surface_spec(scene), note);
}

}  // namespace physarum
