#include "common/map_tools/elevation_proxy.hpp"

#include "common/base/errors.hpp"
#include "common/surface/fe_operators.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace physarum {
namespace {

using Vec3 = Eigen::Vector3d;

// Connected components of the input's triangles (union-find), one label per vertex, and per
// component its triangles.
struct InputComponents {
  std::vector<int> label;
  std::vector<std::vector<std::array<int, 3>>> faces;
};

InputComponents input_components(const InputMesh& input) {
  std::vector<int> parent(static_cast<size_t>(input.vertex_count()));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : input.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = root(t[k]), b = root(t[(k + 1) % 3]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  InputComponents c;
  c.label.assign(parent.size(), -1);
  std::vector<int> of_root(parent.size(), -1);
  for (int v = 0; v < input.vertex_count(); ++v) {
    int& id = of_root[static_cast<size_t>(root(v))];
    if (id < 0) id = static_cast<int>(c.faces.size()), c.faces.emplace_back();
    c.label[static_cast<size_t>(v)] = id;
  }
  for (const auto& t : input.triangles) c.faces[static_cast<size_t>(c.label[static_cast<size_t>(t[0])])].push_back(t);
  return c;
}

// Barycentric lumped mass of the mesh at `positions`.
Eigen::VectorXd lumped_mass_at(const std::vector<Vec3>& positions, const std::vector<std::array<int, 3>>& triangles) {
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(positions.size()));
  for (const auto& t : triangles) {
    const double third = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]).norm() / 6.0;
    for (const int v : t) mass[v] += third;
  }
  return mass;
}

}  // namespace

double enclosed_volume(const std::vector<Vec3>& positions, const std::vector<std::array<int, 3>>& faces) {
  double six_volume = 0.0;
  for (const auto& t : faces) six_volume += positions[t[0]].dot(positions[t[1]].cross(positions[t[2]]));
  return six_volume / 6.0;
}

namespace {

// The fixed stiffness of the input geometry.
Eigen::SparseMatrix<double> input_laplacian(const IntrinsicMesh& mesh, const InputMesh& input, const std::string& where) {
  Eigen::SparseMatrix<double> laplacian;
  try {
    laplacian = cotan_laplacian(mesh);
  } catch (const InputError& error) {
    throw InputError(where + ": the input mesh " + input.source + " cannot be smoothed: " + error.what());
  }
  return laplacian;
}

// The boundary (held in place) from the mesh's halfedges: per vertex, and per component whether it
// has any (an open component keeps no volume).
void mark_boundary(const IntrinsicMesh& mesh, const InputComponents& components, std::vector<bool>& on_boundary,
                   std::vector<bool>& component_open) {
  for (int f = 0; f < mesh.face_count(); ++f)
    for (int i = 0; i < 3; ++i)
      if (mesh.twin[f][i] < 0)
        for (const int v : {mesh.faces[f][i], mesh.faces[f][(i + 1) % 3]}) {
          on_boundary[static_cast<size_t>(v)] = true;
          component_open[static_cast<size_t>(components.label[static_cast<size_t>(v)])] = true;
        }
}

// Free vertices, and the parts of L that couple them to each other and to the held boundary.
struct FreeSystem {
  std::vector<int> free_vertex;
  Eigen::SparseMatrix<double> stiffness;  // L_ff
  Eigen::MatrixXd boundary_load;          // L_fb X_b, constant in time
};

FreeSystem free_system(const Eigen::SparseMatrix<double>& laplacian, const std::vector<bool>& on_boundary,
                       const InputMesh& input) {
  const int n = input.vertex_count();
  std::vector<int> free_index(static_cast<size_t>(n), -1);
  std::vector<int> free_vertex;
  for (int v = 0; v < n; ++v)
    if (!on_boundary[static_cast<size_t>(v)]) free_index[static_cast<size_t>(v)] = static_cast<int>(free_vertex.size()), free_vertex.push_back(v);
  const int m = static_cast<int>(free_vertex.size());
  std::vector<Eigen::Triplet<double>> free_free;
  Eigen::MatrixXd boundary_load = Eigen::MatrixXd::Zero(m, 3);  // L_fb X_b, constant in time
  for (int k = 0; k < laplacian.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian, k); it; ++it) {
      const int i = free_index[static_cast<size_t>(it.row())];
      if (i < 0) continue;
      const int j = free_index[static_cast<size_t>(it.col())];
      if (j >= 0)
        free_free.emplace_back(i, j, it.value());
      else
        boundary_load.row(i) += it.value() * input.positions[static_cast<size_t>(it.col())].transpose();
    }
  Eigen::SparseMatrix<double> stiffness(m, m);
  stiffness.setFromTriplets(free_free.begin(), free_free.end());
  return FreeSystem{std::move(free_vertex), std::move(stiffness), std::move(boundary_load)};
}

// 1. The flow, the mass updated every step (the system's pattern analysed once): `steps` backward
// Euler steps of length h, moving the free vertices of x.
void mean_curvature_flow(const InputMesh& input, const FreeSystem& system, double h, int steps, const std::string& where,
                         std::vector<Vec3>& x) {
  const std::vector<int>& free_vertex = system.free_vertex;
  const int m = static_cast<int>(free_vertex.size());
  if (m > 0) {
    // L_ff's diagonal is stored (every free vertex has a face), so adding the mass keeps the
    // pattern: it is analysed once.
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
    solver.analyzePattern(system.stiffness);
    for (int step = 0; step < steps; ++step) {
      const Eigen::VectorXd mass = lumped_mass_at(x, input.triangles);
      Eigen::SparseMatrix<double> a = h * system.stiffness;
      Eigen::MatrixXd rhs(m, 3);
      for (int i = 0; i < m; ++i) {
        const int v = free_vertex[static_cast<size_t>(i)];
        a.coeffRef(i, i) += mass[v];
        rhs.row(i) = mass[v] * x[static_cast<size_t>(v)].transpose() - h * system.boundary_load.row(i);
      }
      solver.factorize(a);
      if (solver.info() != Eigen::Success)
        throw InputError(where + ": the mean-curvature flow of " + input.source + " could not be solved (step " +
                         std::to_string(step + 1) + ")");
      const Eigen::MatrixXd next = solver.solve(rhs);
      for (int i = 0; i < m; ++i) x[static_cast<size_t>(free_vertex[static_cast<size_t>(i)])] = next.row(i).transpose();
    }
  }
}

// 2. Each closed component back to its own volume, about its volume centroid.
void restore_closed_volumes(const InputMesh& input, const InputComponents& components,
                            const std::vector<bool>& component_open, double time, const std::string& where,
                            std::vector<Vec3>& x) {
  const int n = input.vertex_count();
  for (size_t c = 0; c < components.faces.size(); ++c) {
    if (component_open[c]) continue;
    const auto& faces = components.faces[c];
    const double original = enclosed_volume(input.positions, faces), smoothed = enclosed_volume(x, faces);
    if (!(std::abs(smoothed) > 1e-12 * std::abs(original)) || !(original * smoothed > 0.0))
      throw InputError(where + ": the smoothed copy of " + input.source + " collapsed (enclosed volume " +
                       std::to_string(smoothed) + " from " + std::to_string(original) + "): \"time\" = " +
                       std::to_string(time) + " is too long for this shape");
    // Volume centroid: each face's tetrahedron with the origin, weighted by its signed volume.
    Vec3 centroid = Vec3::Zero();
    for (const auto& t : faces)
      centroid += (x[t[0]] + x[t[1]] + x[t[2]]) / 4.0 * (x[t[0]].dot(x[t[1]].cross(x[t[2]])) / 6.0);
    centroid /= smoothed;
    const double scale = std::cbrt(original / smoothed);
    for (int v = 0; v < n; ++v)
      if (components.label[static_cast<size_t>(v)] == static_cast<int>(c)) x[static_cast<size_t>(v)] = centroid + scale * (x[static_cast<size_t>(v)] - centroid);
  }
}

// 3. Signed distance along the outward vertex normal.
InputVertexData<double> signed_distance_along_normals(const InputMesh& input, const std::vector<Vec3>& x) {
  const int n = input.vertex_count();
  std::vector<Vec3> normal(static_cast<size_t>(n), Vec3::Zero());
  for (const auto& t : input.triangles) {
    const Vec3 face_normal = (input.positions[t[1]] - input.positions[t[0]]).cross(input.positions[t[2]] - input.positions[t[0]]);
    for (const int v : t) normal[static_cast<size_t>(v)] += face_normal;  // |face_normal| = 2 area: area-weighted
  }
  InputVertexData<double> signed_distance(static_cast<size_t>(n), 0.0);
  for (int v = 0; v < n; ++v) {
    const Vec3& nv = normal[static_cast<size_t>(v)];
    if (nv.norm() > 0.0) signed_distance[v] = (input.positions[static_cast<size_t>(v)] - x[static_cast<size_t>(v)]).dot(nv.normalized());
  }
  return signed_distance;
}

// 4. Normalised, without stretching a relief below the floor.
InputVertexData<double> normalised_relief(const InputVertexData<double>& signed_distance, double diagonal) {
  const int n = static_cast<int>(signed_distance.size());
  const auto [low, high] = std::minmax_element(signed_distance.begin(), signed_distance.end());
  const double mid = 0.5 * (*low + *high), width = std::max(*high - *low, kElevationReliefFloor * diagonal);
  InputVertexData<double> value(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v) value[v] = std::clamp(0.5 + (signed_distance[v] - mid) / width, 0.0, 1.0);
  return value;
}

}  // namespace

ElevationProxy elevation_proxy(const InputMesh& input, double time, int steps, const std::string& where) {
  if (!std::isfinite(time) || !(time > 0.0))
    throw InputError(where + ": \"time\" = " + std::to_string(time) + " must be a positive finite time");
  if (steps < 1) throw InputError(where + ": \"steps\" = " + std::to_string(steps) + " must be at least 1");
  const int n = input.vertex_count();
  const InputMeshStatistics statistics = compute_statistics(input);
  const double diagonal = statistics.bounding_box_diagonal;
  if (!(diagonal > 0.0)) throw InputError(where + ": the input mesh " + input.source + " has no extent to smooth");

  // The fixed stiffness of the input geometry, and the boundary (held in place) from its halfedges.
  IntrinsicMesh mesh = intrinsic_mesh_from_input(input);
  const Eigen::SparseMatrix<double> laplacian = input_laplacian(mesh, input, where);
  const InputComponents components = input_components(input);
  std::vector<bool> on_boundary(static_cast<size_t>(n), false), component_open(components.faces.size(), false);
  mark_boundary(mesh, components, on_boundary, component_open);
  const FreeSystem system = free_system(laplacian, on_boundary, input);

  std::vector<Vec3> x = input.positions;
  const double h = time * diagonal * diagonal / steps;
  mean_curvature_flow(input, system, h, steps, where, x);
  restore_closed_volumes(input, components, component_open, time, where, x);

  ElevationProxy out;
  out.signed_distance = signed_distance_along_normals(input, x);
  out.value = normalised_relief(out.signed_distance, diagonal);
  out.smoothed = std::move(x);
  return out;
}

}  // namespace physarum
