#pragma once
// Seed sets: the intrinsic vertices a map tool starts from (the geodesic distance's "from", and the
// regions of a Laplace solve). One JSON value, four shapes:
//   "NAME"                              the vertices where the scalar map NAME is >= 0.5 (a region,
//                                       a thresholded map, ...)
//   {"points": [[x, y, z], ...]}        the intrinsic vertex nearest to each point (straight-line
//                                       distance, INPUT coordinates like every map coordinate)
//   {"boundary": true}                  every boundary vertex
//   {"boundary": {"spacing": s}}        points stippled along every boundary loop every s metres of
//                                       boundary length, each snapped to the nearest boundary vertex
//                                       along the loop (the ginkgo margin of Fig. 18). s is measured
//                                       on the SIMULATED surface, i.e. after scale_to_area (the
//                                       surface's own units, like sensor_distance), not in input units.
// Parsing (parse_seed_set) needs no surface and refuses malformed sets before anything is built;
// seed_vertices() finds the vertices on a prepared surface.
#include "common/base/element_data.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace physarum {

struct SurfaceDomain;

struct SeedRegion {
  std::string map;  // a scalar map's name
};
struct SeedPoints {
  std::vector<Eigen::Vector3d> points;  // input coordinates, at least one
};
struct SeedBoundary {
  std::optional<double> spacing;  // none: every boundary vertex; else > 0, simulation units
};

struct SeedSet {
  std::variant<SeedRegion, SeedPoints, SeedBoundary> source;
  // The maps it reads (the region's name), so that map sets can order themselves.
  std::vector<std::string> map_dependencies() const;
};

// InputError "WHERE: PROBLEM" for a value of none of the shapes above, an empty point list, a point
// that is not three finite numbers, "boundary" other than true or {"spacing": s}, s <= 0 or not finite.
SeedSet parse_seed_set(const nlohmann::json& value, const std::string& where);

// What seed_vertices() reads from a prepared surface.
struct SeedSurface {
  const SurfaceDomain& domain;
  const std::vector<Eigen::Vector3d>& vertex_position;  // each intrinsic vertex in input coordinates
  // The scalar map of that name (a region's); called only for SeedRegion.
  std::function<const IntrinsicVertexData<double>&(const std::string&)> scalar_map;
};

// The seed vertices, sorted and without repeats. InputError "WHERE: PROBLEM" when a region is >= 0.5
// at no vertex (its largest value is given), or boundary seeds are asked on a surface without
// boundary. Never returns an empty set.
std::vector<int> seed_vertices(const SeedSet& seeds, const SeedSurface& surface, const std::string& where);

// A closed loop of boundary edges: its vertices in order along the boundary (the surface on the
// left), starting at the loop's lowest vertex id, and the length of the edge from vertices[i] to
// vertices[i + 1] (the last one back to the first).
struct BoundaryLoop {
  std::vector<int> vertices;
  std::vector<double> edge_length;
};
// Every boundary loop of the domain; none for a closed surface.
std::vector<BoundaryLoop> boundary_loops(const SurfaceDomain& domain);

}  // namespace physarum
