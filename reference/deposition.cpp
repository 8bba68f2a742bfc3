#include "reference/deposition.hpp"

#include <algorithm>

namespace physarum {

namespace {

// Splits `amount` over the three corners of `face` by the barycentric weights of `point`.
void deposit_at_point(const SurfaceDomain& domain, int face, const Eigen::Vector2d& point, double amount,
                      IntrinsicVertexData<double>& amount_per_vertex) {
  const Eigen::Vector3d b = barycentric_in_face(domain, face, point);
  const std::array<int, 3>& v = domain.face_vertices[face];
  for (int k = 0; k < 3; ++k) amount_per_vertex[v[k]] += amount * b[k];
}

}  // namespace

void deposit_along_path(const SurfaceDomain& domain, const std::vector<TraceSegment>& segments, double amount,
                        int face, const Eigen::Vector2d& position, IntrinsicVertexData<double>& amount_per_vertex) {
  if (amount == 0.0) return;
  double path_length = 0.0;
  for (const TraceSegment& s : segments) path_length += (s.end - s.start).norm();
  if (path_length <= 0.0) {
    deposit_at_point(domain, face, position, amount, amount_per_vertex);
    return;
  }
  // Eq. 4 with linear basis functions: a segment's share of the line integral is its length over
  // the path length, and the average of a linear function along it is its value at the midpoint.
  for (const TraceSegment& s : segments) {
    const double share = (s.end - s.start).norm() / path_length;
    deposit_at_point(domain, s.face, 0.5 * (s.start + s.end), amount * share, amount_per_vertex);
  }
}

double active_fraction(double age, double dt, double activation_time) {
  if (dt <= 0.0) return age >= activation_time ? 1.0 : 0.0;
  return std::clamp((age + dt - activation_time) / dt, 0.0, 1.0);
}

}  // namespace physarum
