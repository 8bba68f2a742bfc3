#include "common/map_tools/surface_gradient.hpp"

#include "common/surface/fe_operators.hpp"

#include <Eigen/Geometry>

namespace physarum {
namespace {

Eigen::Vector2d face_gradient_of(const SurfaceDomain& domain, int f, const IntrinsicVertexData<double>& values) {
  const std::array<int, 3>& v = domain.face_vertices[f];
  return face_gradient(domain, f, {values[v[0]], values[v[1]], values[v[2]]});
}

}  // namespace

IntrinsicFaceData<std::array<double, 2>> gradient_vector_map(const SurfaceDomain& domain,
                                                             const IntrinsicVertexData<double>& values, bool normalize) {
  IntrinsicFaceData<std::array<double, 2>> out(static_cast<size_t>(domain.face_count));
  for (int f = 0; f < domain.face_count; ++f) {
    Eigen::Vector2d g = face_gradient_of(domain, f, values);
    if (normalize) g = g.norm() > 0.0 ? Eigen::Vector2d(g.normalized()) : Eigen::Vector2d(Eigen::Vector2d::Zero());
    out[f] = {g.x(), g.y()};
  }
  return out;
}

std::vector<Eigen::Vector3d> input_face_gradients(const InputMesh& input, const InputVertexData<double>& values,
                                                  bool normalize) {
  std::vector<Eigen::Vector3d> out(static_cast<size_t>(input.triangle_count()), Eigen::Vector3d::Zero());
  for (int f = 0; f < input.triangle_count(); ++f) {
    const std::array<int, 3>& t = input.triangles[static_cast<size_t>(f)];
    const Eigen::Vector3d normal =
        (input.positions[t[1]] - input.positions[t[0]]).cross(input.positions[t[2]] - input.positions[t[0]]);
    const double two_area_squared = normal.squaredNorm();
    if (!(two_area_squared > 0.0)) continue;
    // grad u = sum_k u_k (N x e_k) / |N|^2 with e_k the edge opposite corner k, run counter-clockwise.
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = input.positions[t[(k + 2) % 3]] - input.positions[t[(k + 1) % 3]];
      g += values[t[k]] * normal.cross(e);
    }
    g /= two_area_squared;
    if (normalize) g = g.norm() > 0.0 ? Eigen::Vector3d(g.normalized()) : Eigen::Vector3d(Eigen::Vector3d::Zero());
    out[static_cast<size_t>(f)] = g;
  }
  return out;
}

IntrinsicVertexData<double> gradient_magnitude_per_vertex(const SurfaceDomain& domain,
                                                          const IntrinsicVertexData<double>& values) {
  std::vector<double> weighted(static_cast<size_t>(domain.vertex_count), 0.0), area(weighted.size(), 0.0);
  for (int f = 0; f < domain.face_count; ++f) {
    const double magnitude = face_gradient_of(domain, f, values).norm();
    for (const int v : domain.face_vertices[f]) {
      weighted[static_cast<size_t>(v)] += domain.face_area[f] * magnitude;
      area[static_cast<size_t>(v)] += domain.face_area[f];
    }
  }
  IntrinsicVertexData<double> slope(static_cast<size_t>(domain.vertex_count), 0.0);
  for (int v = 0; v < domain.vertex_count; ++v)
    if (area[static_cast<size_t>(v)] > 0.0) slope[v] = weighted[static_cast<size_t>(v)] / area[static_cast<size_t>(v)];
  return slope;
}

}  // namespace physarum
