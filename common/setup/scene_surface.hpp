#pragma once
// A scene's surface: the keys that describe it read off the scene, and the surface prepared from
// them (common/surface/prepared_surface.hpp does the work for any SurfaceSpec).
#include "common/scene/scene.hpp"
#include "common/surface/prepared_surface.hpp"

namespace physarum {

// The scene's mesh, scale_to_area, max_circumradius and min_angle.
SurfaceSpec surface_spec(const Scene& scene);

// prepare_surface(surface_spec(scene)).
PreparedSurface prepare_scene_surface(const Scene& scene, const SurfaceNote& note = {});

}  // namespace physarum
