#pragma once
// Outflow extrapolation of a per-face direction field at the boundary of a surface, for the heat
// method's unit field when the heat is the Neumann solution alone (common/map_tools/heat_geodesic.hpp).
//
// A Neumann boundary keeps heat in: the discrete heat's gradient turns to run along the boundary in
// the faces that touch it, so its level sets meet the boundary at right angles. That is right where
// the geodesics run along the boundary and wrong where they leave the surface through it: there the
// field in the boundary faces bends by up to ~37 degrees (measured on shape:square from a corner),
// the distance stops growing over the last ring of faces, and the far corner's distance comes out
// 2.45 % of the diagonal off. The field one ring further in does not see the boundary, and its
// direction changes slowly (by about h / r over a ring at distance r from the source). So, as an
// outflow boundary condition extrapolates from the interior, each boundary face whose interior
// direction points out of the surface takes that direction; the others keep their own.
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <vector>

namespace physarum {

// A face's direction (in its own frame), or nothing where the field has none.
using FaceDirection = std::function<std::optional<Eigen::Vector2d>(int face)>;

struct FaceDirectionOverride {
  int face;
  Eigen::Vector2d direction;  // unit, in the face's frame
};

// For every face with a corner on the boundary (on_boundary, per vertex) and none in `keep` (per
// vertex: e.g. the seeds, whose faces carry a direction of their own): the normalised sum of
// `field` over the nearest faces without a boundary corner (found by stepping across interior
// edges, at most four steps; carried into this face's frame across each edge), when that points out
// of the surface, i.e. has a positive component along the outward normal of the boundary at the
// face's boundary corners (the mean of the two boundary edges' normals at each, carried around the
// corner's fan). Returned in increasing face order; faces left as they are are not listed.
std::vector<FaceDirectionOverride> outflow_directions(const SurfaceDomain& domain, const std::vector<char>& on_boundary,
                                                      const std::vector<char>& keep, const FaceDirection& field);

}  // namespace physarum
