#pragma once
// Spots drawn on a mesh's surface (a JSON sketch's "surface_point" ellipses, common/sketch/sketch.hpp)
// placed on it, each its own region: its attributes are measured along the surface and blended over
// it by geodesic distance, as a window sketch's regions are blended over the window.
//
//   placing   each mark's point is projected onto the input surface (its closest point), its
//             direction into the tangent plane of the face there; the mark's major axis is that
//             direction (or the one across it when the first radius is the minor one);
//   distance  fast marching (common/map_tools/fast_marching.hpp) from each mark over the input
//             mesh with the marks inserted as vertices (their faces split in three), so that a
//             distance starts at the mark itself rather than at a vertex near it: exact on a flat
//             surface;
//   spacing   a mark's geodesic distance to its nearest other mark (the neighbours a window sketch
//             finds by Delaunay are here the geodesic nearest);
//   blend     Shepard's inverse-distance weights with geodesic distances, 1 / d^4 normalised: each
//             mark's own value at its point, a smooth mixture between marks.
#include "common/mesh/closest_point.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/sketch/sketch.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <vector>

namespace physarum {

struct SurfaceMarks {
  std::vector<Eigen::Vector3d> point;   // on the surface
  std::vector<Eigen::Vector3d> axis;    // the major axis, a unit tangent vector
  std::vector<Eigen::Vector3d> normal;  // the surface's unit normal at the point
  std::vector<double> area, aspect;     // input units^2 (pi a b); minor / major
  std::vector<double> spacing;          // input units, to the nearest other mark (0: a single mark)
  std::vector<std::vector<double>> distance;  // [input vertex][mark], input units

  size_t size() const { return point.size(); }
  // Each mark's weight at an input vertex, or at a point on (or near) the input surface (the
  // distances interpolated linearly over its closest face); they sum to 1.
  std::vector<double> weights(size_t vertex) const;
  std::vector<double> weights(const Eigen::Vector3d& input_point) const;
  // Each mark's distance (input units) to a point on (or near) the input surface, interpolated.
  std::vector<double> distances(const Eigen::Vector3d& input_point) const;
  // Where a point on the surface lies against mark k's ellipse: sqrt(a^2 / A^2 + b^2 / B^2) for the
  // semi-axes A, B and the point's offsets a along the axis, b across it in the mark's tangent plane
  // (a mark is small against the surface's curvature): < 1 inside, 1 on the rim; infinity where the
  // point lies farther along the surface than twice the major radius (the far side of a thin part).
  double ellipse_radius(size_t k, const Eigen::Vector3d& input_point) const;
  // The mark nearest (along the surface) to a point on the input surface.
  int nearest(const Eigen::Vector3d& input_point) const;

  const InputMesh* mesh = nullptr;  // the input mesh, which must outlive the marks
  std::shared_ptr<const FaceLocator> locator;
};

// The marks of `sketch` placed on `mesh` (which must outlive them). InputError naming the mark: a point farther from the surface than a tenth of the mesh's bounding
// box diagonal, a direction (nearly) normal to the surface at its point, or a mesh with a connected
// piece that no mark lies on (distances could not reach it).
SurfaceMarks place_surface_marks(const Sketch& sketch, const InputMesh& mesh);

// sketch.json's "surface_marks": per mark its point on the surface, area, aspect, axis and spacing.
nlohmann::ordered_json surface_marks_json(const SurfaceMarks& marks);

}  // namespace physarum
