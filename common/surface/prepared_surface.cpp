#include "common/surface/prepared_surface.hpp"

#include "common/base/errors.hpp"
#include "common/surface/field_transfer.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/intrinsic/refinement_estimate.hpp"

#include <cmath>
#include <utility>

namespace physarum {

PreparedSurface prepare_surface(InputMesh input, const SurfaceSpec& spec, const SurfaceNote& note) {
  PreparedSurface s;
  s.input = std::move(input);
  for (const std::string& w : s.input.warnings) s.warnings.push_back(s.input.source + ": " + w);
  s.simulated = s.input;
  if (spec.scale_to_area) {
    const double area = compute_statistics(s.input).area;
    if (!(area > 0.0))
      throw InputError(s.input.source + ": surface area " + std::to_string(area) + " cannot be scaled");
    const double factor = std::sqrt(*spec.scale_to_area / area);
    for (Eigen::Vector3d& p : s.simulated.positions) p *= factor;
  }
  const InputMeshStatistics scaled = compute_statistics(s.simulated);
  s.diameter = scaled.bounding_box_diagonal;
  IntrinsicTriangulation triangulation(s.simulated);
  triangulation.flip_to_delaunay();
  if (spec.max_circumradius || spec.min_angle_deg > 0.0) {
    RefinementOptions refinement;
    if (spec.max_circumradius) refinement.max_circumradius = *spec.max_circumradius;
    refinement.min_angle_deg = spec.min_angle_deg;
    const RefinementEstimate estimate =
        check_refinement_size(s.input.source, scaled.area, triangulation.vertex_count(), refinement);
    if (note && estimate.vertices >= kRefinementNoteVertices) note(estimate.describe());
    triangulation.refine(refinement);
  }
  s.domain = build_surface_domain(triangulation.snapshot());
  // The intrinsic vertices sit on the SCALED input, whose connectivity is the input's, so the same
  // map carries fields back onto the input in its own coordinates.
  s.input_to_intrinsic = input_vertex_to_intrinsic(s.simulated, s.domain.vertex_location);
  return s;
}

PreparedSurface prepare_surface(const SurfaceSpec& spec, const SurfaceNote& note) {
  return prepare_surface(load_mesh(spec.mesh), spec, note);
}

}  // namespace physarum
