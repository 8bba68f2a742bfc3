#include "common/mesh/input_mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace physarum {
namespace {

std::uint64_t directed_key(int from, int to) { return (std::uint64_t{static_cast<std::uint32_t>(from)} << 32) | static_cast<std::uint32_t>(to); }

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

double bounding_box_diagonal(const InputMesh& mesh) {
  if (mesh.positions.empty()) return 0.0;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

InputMeshStatistics compute_statistics(const InputMesh& mesh) {
  InputMeshStatistics s;
  const int n = mesh.vertex_count();
  s.vertices = n;
  s.faces = mesh.triangle_count();

  // Directed halfedges; an undirected edge is counted once, from the halfedge whose reverse is
  // absent or which runs from the smaller to the larger vertex.
  std::unordered_map<std::uint64_t, int> halfedge_count;
  halfedge_count.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++halfedge_count[directed_key(t[k], t[(k + 1) % 3])];

  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& t : mesh.triangles) {
    parent[find_root(parent, t[0])] = find_root(parent, t[1]);
    parent[find_root(parent, t[0])] = find_root(parent, t[2]);
  }

  struct Counts {
    long vertices = 0, edges = 0, faces = 0, boundary_loops = 0;
  };
  std::unordered_map<int, Counts> per_component;
  for (int v = 0; v < n; ++v) ++per_component[find_root(parent, v)].vertices;
  for (const auto& t : mesh.triangles) ++per_component[find_root(parent, t[0])].faces;

  // Boundary halfedges (no reverse), chained into loops by their start vertex.
  std::unordered_multimap<int, int> boundary_from;
  for (const auto& [key, count] : halfedge_count) {
    const int from = static_cast<int>(key >> 32), to = static_cast<int>(key & 0xffffffffu);
    const bool reverse_present = halfedge_count.contains(directed_key(to, from));
    if (!reverse_present || from < to) ++per_component[find_root(parent, from)].edges;
    if (!reverse_present) boundary_from.emplace(from, to);
  }
  while (!boundary_from.empty()) {
    const int start = boundary_from.begin()->first;
    int at = start;
    ++per_component[find_root(parent, start)].boundary_loops;
    while (true) {
      auto it = boundary_from.find(at);
      if (it == boundary_from.end()) break;
      at = it->second;
      boundary_from.erase(it);
      if (at == start) break;
    }
  }

  for (const auto& [root, c] : per_component) {
    ++s.components;
    s.edges += static_cast<int>(c.edges);
    s.boundary_loops += static_cast<int>(c.boundary_loops);
    const long euler = c.vertices - c.edges + c.faces;
    s.genus += static_cast<int>((2 - euler - c.boundary_loops) / 2);
  }

  s.bounding_box_diagonal = bounding_box_diagonal(mesh);
  for (const auto& t : mesh.triangles)
    s.area += 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]).norm();
  return s;
}

}  // namespace physarum
