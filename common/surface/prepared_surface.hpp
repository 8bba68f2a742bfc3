#pragma once
// The surface a simulation runs on, prepared in ONE place for everything that simulates (run,
// compare, bench, the benchmark suites, the device check): the input mesh as loaded, the same mesh
// scaled to the requested area, its intrinsic Delaunay triangulation refined as asked, the surface
// domain, and the map that carries per-vertex results back onto the input mesh.
//   load (and repair) -> scale to area -> flip to Delaunay -> refine -> SurfaceDomain
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/surface/surface_domain.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// What surface to build (the scene keys mesh, scale_to_area, max_circumradius, min_angle; a scene's
// own is common/setup/scene_surface.hpp: surface_spec).
struct SurfaceSpec {
  std::string mesh;                        // file path or "shape:NAME" (load_mesh's spec)
  std::optional<double> scale_to_area;     // rescale the input so its area is this many m^2
  std::optional<double> max_circumradius;  // intrinsic refinement bound, in scaled units
  double min_angle_deg = 0.0;              // refinement angle bound; 0 = none
};

struct PreparedSurface {
  InputMesh input;      // as loaded (repaired), in the file's own coordinates
  InputMesh simulated;  // scaled about the origin so its area is spec.scale_to_area (or = input)
  SurfaceDomain domain;
  InputVertexData<int> input_to_intrinsic;  // intrinsic vertex sitting on each input vertex
  std::vector<std::string> warnings;    // repairs made while loading, for the command line
  double diameter = 0.0;                // bounding-box diagonal of `simulated` (scaled units)
};

// Called with one line before a refinement estimated to be long starts (for the command line).
using SurfaceNote = std::function<void(const std::string&)>;

// Loads spec.mesh, scales, flips to intrinsic Delaunay and refines when the spec gives
// max_circumradius or min_angle. Refuses (InputError, before refining) a bound whose estimated
// vertex count exceeds the refinement's insertion budget. Throws InputError naming the mesh on any
// failure.
PreparedSurface prepare_surface(const SurfaceSpec& spec, const SurfaceNote& note = {});
// The same from a mesh built in code (spec.mesh is then only its name for messages).
PreparedSurface prepare_surface(InputMesh input, const SurfaceSpec& spec, const SurfaceNote& note = {});

}  // namespace physarum
