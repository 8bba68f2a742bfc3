#pragma once
// The surface a scene simulates on, prepared once for every command that runs a scene (run,
// compare, bench): the input mesh as loaded, the same mesh scaled to the scene's area, its intrinsic
// Delaunay triangulation refined as the scene asks, the surface domain, and the map that carries
// per-vertex results back onto the input mesh.
#include "common/element_data.hpp"
#include "common/input_mesh.hpp"
#include "common/scene.hpp"
#include "common/surface_domain.hpp"

#include <string>
#include <vector>

namespace physarum {

struct SceneSurface {
  InputMesh input;      // as loaded (repaired), in the file's own coordinates
  InputMesh simulated;  // scaled about the origin so its area is scene.scale_to_area (or = input)
  SurfaceDomain domain;
  InputVertexData<int> input_to_intrinsic;  // intrinsic vertex sitting on each input vertex
  std::vector<std::string> warnings;    // repairs made while loading, for the command line
};

// Loads scene.mesh, scales, flips to intrinsic Delaunay and refines when the scene gives
// max_circumradius or min_angle. Throws InputError naming the mesh on any failure.
SceneSurface prepare_scene_surface(const Scene& scene);

}  // namespace physarum
