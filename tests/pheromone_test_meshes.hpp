#pragma once
// Small meshes built inline for the tests, so they depend only on the code under test and not on
// mesh loading or intrinsic refinement.
#include "common/surface/fe_operators.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>
#include <utility>

namespace physarum::testing {

// Unit icosphere: an icosahedron subdivided `levels` times, vertices pushed onto the sphere
// (10 * 4^levels + 2 vertices), faces oriented counter-clockwise seen from outside.
inline InputMesh make_icosphere(int levels) {
  InputMesh mesh;
  mesh.source = "inline icosphere";
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  const double raw[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                             {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (const auto& p : raw) mesh.positions.push_back(Eigen::Vector3d(p[0], p[1], p[2]).normalized());
  mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                    {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      mesh.positions.push_back((mesh.positions[a] + mesh.positions[b]).normalized());
      const int id = static_cast<int>(mesh.positions.size()) - 1;
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : mesh.triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    mesh.triangles = std::move(finer);
  }
  // Orient every face outward (normal along the centroid), whatever order the table above used.
  for (auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[t[0]];
    const Eigen::Vector3d n = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
    if (n.dot(a + mesh.positions[t[1]] + mesh.positions[t[2]]) < 0) std::swap(t[1], t[2]);
  }
  for (int v = 0; v < mesh.vertex_count(); ++v) mesh.file_vertex.push_back(v);
  return mesh;
}

// Flat unit square [0,1]^2 in z = 0 with n x n cells, each cut into two triangles (CCW seen from
// +z): all along the same diagonal, or along alternating diagonals when `alternating`. Interior
// vertices are optionally jittered in the plane by up to jitter / n in x and y (uniform, from
// `seed`), which keeps the mesh flat and valid for jitter < 0.5.
inline InputMesh make_square_grid(int n, bool alternating = false, double jitter = 0.0, unsigned seed = 1) {
  InputMesh mesh;
  mesh.source = "inline square";
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Eigen::Vector3d p(double(i) / n, double(j) / n, 0.0);
      if (jitter > 0.0 && i > 0 && i < n && j > 0 && j < n) p += Eigen::Vector3d(u(rng), u(rng), 0.0) / n;
      mesh.positions.push_back(p);
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (!alternating || (i + j) % 2 == 0) {
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({a, c, d});
      } else {
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({b, c, d});
      }
    }
  for (int v = 0; v < mesh.vertex_count(); ++v) mesh.file_vertex.push_back(v);
  return mesh;
}

// The surface domain of a mesh taken as it is (no flips): enough for the pheromone operators.
inline SurfaceDomain make_domain(const InputMesh& mesh) {
  return build_surface_domain(intrinsic_mesh_from_input(mesh));
}

}  // namespace physarum::testing
