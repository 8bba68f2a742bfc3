#pragma once
// Splitting one input polygon into triangles by ear clipping in the polygon's best-fit plane.
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <span>
#include <unordered_set>
#include <vector>

namespace physarum {

// Key of the undirected edge {a, b}, for the edge sets below.
inline std::uint64_t undirected_edge_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(a < b ? a : b), hi = static_cast<std::uint32_t>(a < b ? b : a);
  return (std::uint64_t{hi} << 32) | lo;
}

// Triangulates the polygon with corners `vertices` (indices into positions, all distinct) into
// vertices.size() - 2 triangles, returned as triples of CORNER numbers (0 .. size-1) so that
// per-corner data can follow, in the polygon's own orientation.
//
// Ear clipping: among the ears that are convex and empty in the plane of the polygon's Newell
// normal, the one with the largest smallest angle is cut first. A diagonal that already is an
// edge in `existing_edges` is avoided whenever possible, because it would put more than two
// triangles on one edge (this happens in real files: two quads sharing three vertices). The
// chosen diagonals are added to `existing_edges`.
std::vector<std::array<int, 3>> triangulate_polygon(std::span<const int> vertices,
                                                    const std::vector<Eigen::Vector3d>& positions,
                                                    std::unordered_set<std::uint64_t>& existing_edges);

}  // namespace physarum
