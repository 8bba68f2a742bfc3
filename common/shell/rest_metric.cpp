#include "common/shell/rest_metric.hpp"

#include "common/shell/hinge_bending.hpp"
#include "common/shell/membrane_energy.hpp"

#include <cmath>

namespace physarum {

ShellRestState rest_state_of(const ShellTopology& topology, const std::vector<Eigen::Vector3d>& positions) {
  ShellRestState rest;
  rest.face_metric.reserve(topology.faces.size());
  for (const auto& f : topology.faces) rest.face_metric.push_back(triangle_metric(positions[f[0]], positions[f[1]], positions[f[2]]));
  rest.hinge_angle.reserve(topology.hinges.size());
  for (const ShellHinge& h : topology.hinges) {
    const auto& v = h.vertices;
    rest.hinge_angle.push_back(dihedral_angle(positions[v[0]], positions[v[1]], positions[v[2]], positions[v[3]]));
  }
  return rest;
}

double rest_edge_length_squared(const Eigen::Matrix2d& metric, int corner) {
  switch (corner) {
    case 0: return metric(0, 0) + metric(1, 1) - 2.0 * metric(0, 1);  // |e2 - e1|^2
    case 1: return metric(1, 1);                                      // |e2|^2
    default: return metric(0, 0);                                     // |e1|^2
  }
}

Eigen::Matrix2d metric_from_edge_lengths(const std::array<double, 3>& opposite_squared) {
  const double e1 = opposite_squared[2], e2 = opposite_squared[1];  // |x1 - x0|^2, |x2 - x0|^2
  const double cross = 0.5 * (e1 + e2 - opposite_squared[0]);
  Eigen::Matrix2d metric;
  metric << e1, cross, cross, e2;
  return metric;
}

double hinge_weight(const ShellHinge& hinge, const ShellRestState& rest) {
  const Eigen::Matrix2d& m0 = rest.face_metric[static_cast<std::size_t>(hinge.faces[0])];
  const Eigen::Matrix2d& m1 = rest.face_metric[static_cast<std::size_t>(hinge.faces[1])];
  const double length_squared =
      0.5 * (rest_edge_length_squared(m0, hinge.opposite_corner[0]) + rest_edge_length_squared(m1, hinge.opposite_corner[1]));
  return length_squared / (metric_area(m0) + metric_area(m1));
}

double rest_area(const ShellRestState& rest) {
  double area = 0.0;
  for (const Eigen::Matrix2d& m : rest.face_metric) area += metric_area(m);
  return area;
}

Eigen::Matrix2d grown_metric(const Eigen::Matrix2d& metric, double along, double across,
                             const Eigen::Vector2d& direction) {
  const double norm_squared = direction.dot(metric * direction);  // |d|^2 in the rest metric
  if (!(norm_squared > 0.0)) return across * across * metric;
  // e_i . d_hat for the rest edge vectors e_i; the growth tensor is across^2 I + (along^2 - across^2)
  // d_hat d_hat^T in an orthonormal frame, and the metric its pull-back onto the edge vectors.
  const Eigen::Vector2d projection = metric * direction / std::sqrt(norm_squared);
  return across * across * metric + (along * along - across * across) * projection * projection.transpose();
}

}  // namespace physarum
