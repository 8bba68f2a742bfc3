#include "common/model/domain_sampling.hpp"

#include <cmath>
#include <numbers>

namespace physarum {

FacePoint sample_surface_point(const SurfaceDomain& domain, const PhiloxWords& face_choice, const PhiloxWords& in_face) {
  FacePoint p;
  p.face = domain.face_sampler.sample(first_uniform(face_choice), second_uniform(face_choice));
  const std::array<Eigen::Vector2d, 3>& c = domain.face_corners[p.face];
  const double s = std::sqrt(first_uniform(in_face));
  const double r2 = second_uniform(in_face);
  p.position = (1.0 - s) * c[0] + s * (1.0 - r2) * c[1] + s * r2 * c[2];
  return p;
}

Eigen::Vector2d heading_from_uniform(double u) {
  const double angle = 2.0 * std::numbers::pi * u;
  return {std::cos(angle), std::sin(angle)};
}

double exponential_exposure(double u) { return -std::log(u); }

double interpolate_vertex_field(const SurfaceDomain& domain, const IntrinsicVertexData<double>& vertex_values, int face,
                                const Eigen::Vector2d& position) {
  const Eigen::Vector3d b = barycentric_in_face(domain, face, position);
  const std::array<int, 3>& v = domain.face_vertices[face];
  return b[0] * vertex_values[v[0]] + b[1] * vertex_values[v[1]] + b[2] * vertex_values[v[2]];
}

}  // namespace physarum
