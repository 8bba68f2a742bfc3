// A spot's centre, tangent frame and second-moment shape.
#include "common/pattern/spot_shape.hpp"

#include "common/base/errors.hpp"
#include "common/mesh/closest_point.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace physarum {

SpotShape spot_shape(const InputMesh& mesh, const PatternRegion& region) {
  if (!(region.area > 0.0)) throw InputError(mesh.source + ": a spot of zero area has no shape");
  SpotShape s;
  const Eigen::Vector3d mean = region.mean_position();

  // The centre: the closest point on the spot's triangles.
  double best = std::numeric_limits<double>::infinity();
  for (int f : region.faces) {
    const auto& t = mesh.triangles[static_cast<size_t>(f)];
    const Eigen::Vector3d& a = mesh.positions[static_cast<size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.positions[static_cast<size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.positions[static_cast<size_t>(t[2])];
    const Eigen::Vector3d bary = closest_point_barycentric(mean, a, b, c);
    const Eigen::Vector3d point = bary[0] * a + bary[1] * b + bary[2] * c;
    const double d = (point - mean).squaredNorm();
    if (d < best) {
      best = d;
      s.centre = point;
      s.centre_face = f;
      s.centre_barycentric = bary;
    }
  }
  int corner = 0;
  s.centre_barycentric.maxCoeff(&corner);
  s.centre_vertex = mesh.triangles[static_cast<size_t>(s.centre_face)][static_cast<size_t>(corner)];

  // The tangent frame.
  s.normal = region.normal_sum.norm() > 0.0 ? region.normal_sum.normalized() : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d reference = std::abs(s.normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  s.tangent_u = (reference - reference.dot(s.normal) * s.normal).normalized();
  s.tangent_v = s.normal.cross(s.tangent_u);

  // Local PCA: the covariance of the clipped area in the tangent plane.
  const Eigen::Matrix3d covariance = region.second_moment / region.area - mean * mean.transpose();
  Eigen::Matrix<double, 3, 2> frame;
  frame << s.tangent_u, s.tangent_v;
  const Eigen::Matrix2d tangent_covariance = frame.transpose() * covariance * frame;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(tangent_covariance);
  const double l_minor = std::max(eigen.eigenvalues()[0], 0.0), l_major = std::max(eigen.eigenvalues()[1], 0.0);
  const Eigen::Vector2d axis = eigen.eigenvectors().col(1);
  s.major_length = 4.0 * std::sqrt(l_major);
  s.minor_length = 4.0 * std::sqrt(l_minor);
  s.aspect_ratio = l_minor > 0.0 ? std::sqrt(l_major / l_minor) : std::numeric_limits<double>::infinity();
  double angle = std::atan2(axis.y(), axis.x()) * 180.0 / M_PI;
  if (angle < 0.0) angle += 180.0;
  if (angle >= 180.0) angle -= 180.0;
  s.orientation_deg = angle;
  s.major_axis = (axis.x() * s.tangent_u + axis.y() * s.tangent_v).normalized();
  return s;
}

std::optional<double> angle_to_direction_deg(const SpotShape& spot, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d tangent = direction - direction.dot(spot.normal) * spot.normal;
  if (!(tangent.norm() > 1e-9 * std::max(direction.norm(), 1e-300))) return std::nullopt;
  const double c = std::min(1.0, std::abs(tangent.normalized().dot(spot.major_axis)));
  return std::acos(c) * 180.0 / M_PI;
}

}  // namespace physarum
