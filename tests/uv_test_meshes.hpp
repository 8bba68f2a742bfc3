#pragma once
// A small flat mesh with hand-made UVs for the full-resolution and texture tests, so they run without
// the shared meshes: the rectangle [0, 3] x [0, 1] in z = 0, cut into a grid of long thin triangles
// with interior vertices jittered (so flipping to Delaunay moves edges across input edges), and
// mapped to TWO UV charts with a seam at x = 1.5:
//   left  (x <= 1.5): u = 0.05 + 0.4 (x / 1.5),         v = 0.1 + 0.8 y
//   right (x >= 1.5): u = 0.55 + 0.4 ((x - 1.5) / 1.5), v = 0.1 + 0.8 y
// so the charts are u in [0.05, 0.45] and [0.55, 0.95], v in [0.1, 0.9], with gaps between them and
// to the image edges. Vertices on the seam have one UV per chart (per-corner UVs, as OBJ files do).
#include "common/mesh/input_mesh.hpp"

#include <Eigen/Core>
#include <map>
#include <random>
#include <utility>

namespace physarum::testing {

inline Eigen::Vector2d rectangle_chart_uv(const Eigen::Vector3d& p, bool right_chart) {
  return right_chart ? Eigen::Vector2d(0.55 + 0.4 * (p.x() - 1.5) / 1.5, 0.1 + 0.8 * p.y())
                     : Eigen::Vector2d(0.05 + 0.4 * p.x() / 1.5, 0.1 + 0.8 * p.y());
}

// nx must be even (the seam is a grid column).
inline InputMesh make_uv_rectangle(int nx = 8, int ny = 5, double jitter = 0.3, unsigned seed = 7) {
  InputMesh mesh;
  mesh.source = "inline uv rectangle";
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  const double dx = 3.0 / nx, dy = 1.0 / ny;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      Eigen::Vector3d p(i * dx, j * dy, 0.0);
      const bool interior_row = j > 0 && j < ny;
      if (interior_row && i > 0 && i < nx && 2 * i != nx) p.x() += u(rng) * dx;  // the seam column stays straight
      if (interior_row && i > 0 && i < nx) p.y() += u(rng) * dy;
      mesh.positions.push_back(p);
    }
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  std::map<std::pair<int, bool>, int> uv_index;  // (vertex, right chart) -> index into uvs
  auto uv_of = [&](int vertex, bool right) {
    const auto key = std::make_pair(vertex, right);
    auto it = uv_index.find(key);
    if (it != uv_index.end()) return it->second;
    mesh.uvs.push_back(rectangle_chart_uv(mesh.positions[vertex], right));
    return uv_index[key] = static_cast<int>(mesh.uvs.size()) - 1;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      const bool right = 2 * i >= nx;
      for (const std::array<int, 3>& t : {std::array<int, 3>{a, b, c}, std::array<int, 3>{a, c, d}}) {
        mesh.triangles.push_back(t);
        mesh.triangle_uvs.push_back({uv_of(t[0], right), uv_of(t[1], right), uv_of(t[2], right)});
      }
    }
  for (int v = 0; v < mesh.vertex_count(); ++v) mesh.file_vertex.push_back(v);
  return mesh;
}

}  // namespace physarum::testing
