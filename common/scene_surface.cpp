#include "common/scene_surface.hpp"

#include "common/errors.hpp"
#include "common/field_transfer.hpp"
#include "common/intrinsic_triangulation.hpp"
#include "common/mesh_loading.hpp"

#include <cmath>

namespace physarum {

SceneSurface prepare_scene_surface(const Scene& scene) {
  SceneSurface s;
  s.input = load_mesh(scene.mesh);
  for (const std::string& w : s.input.warnings) s.warnings.push_back(s.input.source + ": " + w);
  s.simulated = s.input;
  if (scene.scale_to_area) {
    const double area = compute_statistics(s.input).area;
    if (!(area > 0.0))
      throw InputError(s.input.source + ": surface area " + std::to_string(area) + " cannot be scaled");
    const double factor = std::sqrt(*scene.scale_to_area / area);
    for (Eigen::Vector3d& p : s.simulated.positions) p *= factor;
  }
  IntrinsicTriangulation triangulation(s.simulated);
  triangulation.flip_to_delaunay();
  if (scene.max_circumradius || scene.min_angle_deg > 0.0) {
    RefinementOptions refinement;
    if (scene.max_circumradius) refinement.max_circumradius = *scene.max_circumradius;
    refinement.min_angle_deg = scene.min_angle_deg;
    triangulation.refine(refinement);
  }
  s.domain = build_surface_domain(triangulation.snapshot());
  // The intrinsic vertices sit on the SCALED input, whose connectivity is the input's, so the same
  // map carries fields back onto the input in its own coordinates.
  s.input_to_intrinsic = input_vertex_to_intrinsic(s.simulated, s.domain.vertex_location);
  return s;
}

}  // namespace physarum
