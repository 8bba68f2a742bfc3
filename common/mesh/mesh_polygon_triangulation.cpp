#include "common/mesh/mesh_polygon_triangulation.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {
namespace {

double smallest_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  auto angle = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
    const Eigen::Vector3d u = q - p, v = r - p;
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

// Signed doubled area of the 2D triangle (p, q, r): positive when counter-clockwise.
double orient2d(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(std::span<const int> vertices,
                                                    const std::vector<Eigen::Vector3d>& positions,
                                                    std::unordered_set<std::uint64_t>& existing_edges) {
  const int n = static_cast<int>(vertices.size());
  std::vector<std::array<int, 3>> triangles;
  if (n < 3) return triangles;
  if (n == 3) return {{0, 1, 2}};

  // Newell's normal is robust for non-planar and non-convex polygons.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d& p = positions[vertices[i]];
    const Eigen::Vector3d& q = positions[vertices[(i + 1) % n]];
    normal += Eigen::Vector3d((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()), (p.x() - q.x()) * (p.y() + q.y()));
  }
  if (normal.norm() == 0) normal = Eigen::Vector3d::UnitZ();
  normal.normalize();
  const Eigen::Vector3d axis_u = normal.unitOrthogonal(), axis_w = normal.cross(axis_u);
  std::vector<Eigen::Vector2d> plane(n);
  for (int i = 0; i < n; ++i) plane[i] = {positions[vertices[i]].dot(axis_u), positions[vertices[i]].dot(axis_w)};

  std::vector<int> ring(n);
  for (int i = 0; i < n; ++i) ring[i] = i;
  while (ring.size() > 3) {
    const int m = static_cast<int>(ring.size());
    // Strictness levels: 0 = convex, empty and a new diagonal; 1 = a new diagonal; 2 = anything.
    int best = -1, best_level = 3;
    double best_quality = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < m; ++i) {
      const int a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
      const bool new_diagonal = !existing_edges.contains(undirected_edge_key(vertices[a], vertices[c]));
      bool geometric_ear = orient2d(plane[a], plane[b], plane[c]) > 0;
      for (int j = 0; geometric_ear && j < m; ++j) {
        const int d = ring[j];
        if (d == a || d == b || d == c) continue;
        geometric_ear = !(orient2d(plane[a], plane[b], plane[d]) >= 0 && orient2d(plane[b], plane[c], plane[d]) >= 0 &&
                          orient2d(plane[c], plane[a], plane[d]) >= 0);
      }
      const int level = new_diagonal ? (geometric_ear ? 0 : 1) : 2;
      const double quality = smallest_angle(positions[vertices[a]], positions[vertices[b]], positions[vertices[c]]);
      if (level < best_level || (level == best_level && quality > best_quality)) {
        best = i;
        best_level = level;
        best_quality = quality;
      }
    }
    const int a = ring[(best + m - 1) % m], b = ring[best], c = ring[(best + 1) % m];
    triangles.push_back({a, b, c});
    existing_edges.insert(undirected_edge_key(vertices[a], vertices[c]));
    ring.erase(ring.begin() + best);
  }
  triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

}  // namespace physarum
