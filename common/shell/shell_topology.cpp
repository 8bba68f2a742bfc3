#include "common/shell/shell_topology.hpp"

#include "common/base/errors.hpp"

#include <cstdint>
#include <string>
#include <unordered_map>

namespace physarum {
namespace {

std::uint64_t directed_key(int from, int to) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) | static_cast<std::uint32_t>(to);
}

std::string edge_name(int a, int b) { return "(" + std::to_string(a) + ", " + std::to_string(b) + ")"; }

}  // namespace

ShellTopology build_shell_topology(int vertex_count, const std::vector<std::array<int, 3>>& faces) {
  ShellTopology topology;
  topology.vertex_count = vertex_count;
  topology.faces = faces;
  topology.on_boundary.assign(static_cast<std::size_t>(vertex_count), 0);
  // Each directed edge (a -> b) of a face, with the face and the corner opposite it.
  struct HalfEdge {
    int face, corner;
  };
  std::unordered_map<std::uint64_t, HalfEdge> half_edges;
  half_edges.reserve(faces.size() * 3);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = faces[f][(c + 1) % 3], b = faces[f][(c + 2) % 3];
      if (a < 0 || a >= vertex_count || b < 0 || b >= vertex_count)
        throw InputError("shell: face " + std::to_string(f) + " has a vertex outside 0.." + std::to_string(vertex_count - 1));
      if (!half_edges.emplace(directed_key(a, b), HalfEdge{f, c}).second)
        throw InputError("shell: edge " + edge_name(a, b) +
                         " is used twice in the same direction (inconsistent orientation or a non-manifold edge)");
    }
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = faces[f][(c + 1) % 3], b = faces[f][(c + 2) % 3];
      const auto twin = half_edges.find(directed_key(b, a));
      if (twin == half_edges.end()) {
        topology.on_boundary[static_cast<std::size_t>(a)] = topology.on_boundary[static_cast<std::size_t>(b)] = 1;
        continue;
      }
      if (a > b) continue;  // each interior edge once
      ShellHinge hinge;
      const int g = twin->second.face, d = twin->second.corner;
      hinge.vertices = {a, b, faces[f][c], faces[g][d]};
      hinge.faces = {f, g};
      hinge.opposite_corner = {c, d};
      topology.hinges.push_back(hinge);
    }
  return topology;
}

}  // namespace physarum
