#pragma once
// Meshes built inline for the map-tool tests (tests/test_map_tools_*.cpp), each with a known answer
// in mind: a jittered flat rectangle (linear harmonic functions), a flat annulus (the log profile),
// a sphere with bumps of known places (the elevation proxy), and helpers shared by those tests.
#include "common/mesh/input_mesh.hpp"
#include "common/maps/map_definition.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/setup/scene_surface.hpp"
#include "pheromone_test_meshes.hpp"

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <random>

namespace physarum::testing {

// The rectangle [x0, x1] x [y0, y1] in z = 0, nx x ny cells cut along alternating diagonals,
// interior vertices jittered by up to `jitter` cells (boundary vertices stay on the boundary).
inline InputMesh make_flat_rectangle(double x0, double x1, double y0, double y1, int nx, int ny, double jitter = 0.0,
                                     unsigned seed = 3) {
  InputMesh mesh;
  mesh.source = "inline rectangle";
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  const double dx = (x1 - x0) / nx, dy = (y1 - y0) / ny;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      Eigen::Vector3d p(x0 + i * dx, y0 + j * dy, 0.0);
      if (i > 0 && i < nx) p.x() += u(rng) * dx;
      if (j > 0 && j < ny) p.y() += u(rng) * dy;
      mesh.positions.push_back(p);
    }
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0)
        mesh.triangles.push_back({a, b, c}), mesh.triangles.push_back({a, c, d});
      else
        mesh.triangles.push_back({a, b, d}), mesh.triangles.push_back({b, c, d});
    }
  for (int v = 0; v < mesh.vertex_count(); ++v) mesh.file_vertex.push_back(v);
  return mesh;
}

// The flat annulus inner <= r <= outer in z = 0: `rings` + 1 equally spaced circles of `segments`
// vertices each, every other circle turned by half a segment, so each triangle is isosceles with
// its apex on the next circle: acute everywhere (hence Delaunay, left as it is by the intrinsic
// flips) when the spacing exceeds pi outer / segments. Both boundary circles' vertices lie exactly
// on the circles. (Not a log-polar grid: on one, the cotan Laplacian reproduces log r exactly.)
inline InputMesh make_flat_annulus(double inner, double outer, int segments, int rings) {
  InputMesh mesh;
  mesh.source = "inline annulus";
  for (int k = 0; k <= rings; ++k) {
    const double r = inner + (outer - inner) * k / rings;
    for (int j = 0; j < segments; ++j) {
      const double angle = 2.0 * std::numbers::pi * (j + 0.5 * (k % 2)) / segments;
      mesh.positions.emplace_back(r * std::cos(angle), r * std::sin(angle), 0.0);
    }
  }
  auto id = [segments](int k, int j) { return k * segments + (j % segments); };
  for (int k = 0; k < rings; ++k)
    for (int j = 0; j < segments; ++j) {
      if (k % 2 == 0) {
        mesh.triangles.push_back({id(k, j), id(k, j + 1), id(k + 1, j)});
        mesh.triangles.push_back({id(k, j + 1), id(k + 1, j + 1), id(k + 1, j)});
      } else {
        mesh.triangles.push_back({id(k, j), id(k + 1, j + 1), id(k + 1, j)});
        mesh.triangles.push_back({id(k, j), id(k, j + 1), id(k + 1, j + 1)});
      }
    }
  // Counter-clockwise seen from +z, whatever the order above.
  for (auto& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    if ((b - a).cross(c - a).z() < 0.0) std::swap(t[1], t[2]);
  }
  for (int v = 0; v < mesh.vertex_count(); ++v) mesh.file_vertex.push_back(v);
  return mesh;
}

// The unit icosphere with its radius displaced by amplitude x bumps(p) (p on the unit sphere).
template <class Bumps>
InputMesh make_displaced_sphere(int levels, double amplitude, Bumps bumps) {
  InputMesh mesh = make_icosphere(levels);
  mesh.source = "inline displaced sphere";
  for (Eigen::Vector3d& p : mesh.positions) p *= 1.0 + amplitude * bumps(p);
  return mesh;
}

// The intrinsic vertices' positions in input coordinates (from their barycentrics on the input).
inline std::vector<Eigen::Vector3d> intrinsic_vertex_positions(const PreparedSurface& s) {
  std::vector<Eigen::Vector3d> p(static_cast<size_t>(s.domain.vertex_count));
  for (int v = 0; v < s.domain.vertex_count; ++v) {
    const SurfacePoint& l = s.domain.vertex_location[v];
    const auto& t = s.input.triangles[static_cast<size_t>(l.face)];
    p[static_cast<size_t>(v)] = l.barycentric[0] * s.input.positions[t[0]] + l.barycentric[1] * s.input.positions[t[1]] +
                                l.barycentric[2] * s.input.positions[t[2]];
  }
  return p;
}

inline PreparedSurface surface_from(InputMesh mesh, std::optional<double> max_circumradius = std::nullopt,
                                 std::optional<double> area = std::nullopt) {
  const std::string name = mesh.source;
  return prepare_surface(std::move(mesh), SurfaceSpec{name, area, max_circumradius, 0.0});
}

inline EvaluatedMaps evaluate_json(const nlohmann::json& maps, const PreparedSurface& surface) {
  return evaluate_maps(parse_maps(maps, ".", "scene.json"), surface, "scene.json");
}

}  // namespace physarum::testing
