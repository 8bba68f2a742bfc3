#include "common/shell/hinge_bending.hpp"

#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include <array>
#include <cmath>

namespace physarum {
namespace {

template <typename T>
using Vec3 = std::array<T, 3>;

template <typename T>
Vec3<T> minus(const Vec3<T>& a, const Vec3<T>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <typename T>
Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
template <typename T>
T dot(const Vec3<T>& a, const Vec3<T>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// d theta / d (x0, x1, x2, x3) for any scalar type (double, or AutoDiffScalar for the Hessian).
template <typename T>
std::array<Vec3<T>, 4> angle_gradient(const std::array<Vec3<T>, 4>& x) {
  const Vec3<T> edge = minus(x[1], x[0]);
  const T length_squared = dot(edge, edge);
  const T length = sqrt(length_squared);
  const Vec3<T> normal_a = cross(edge, minus(x[2], x[0]));  // |normal_a| = 2 area = length * height
  const Vec3<T> normal_b = cross(minus(x[3], x[0]), edge);
  const T scale_a = -length / dot(normal_a, normal_a);     // -1 / height along the unit normal
  const T scale_b = -length / dot(normal_b, normal_b);
  // Where the opposite vertices project onto the edge (0 at x0, 1 at x1).
  const T s2 = dot(minus(x[2], x[0]), edge) / length_squared;
  const T s3 = dot(minus(x[3], x[0]), edge) / length_squared;
  std::array<Vec3<T>, 4> g;
  for (int c = 0; c < 3; ++c) {
    const T ga = scale_a * normal_a[c], gb = scale_b * normal_b[c];
    g[2][c] = ga;
    g[3][c] = gb;
    g[0][c] = -(T(1.0) - s2) * ga - (T(1.0) - s3) * gb;
    g[1][c] = -s2 * ga - s3 * gb;
  }
  return g;
}

std::array<Vec3<double>, 4> as_arrays(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                      const Eigen::Vector3d& x3) {
  return {Vec3<double>{x0.x(), x0.y(), x0.z()}, Vec3<double>{x1.x(), x1.y(), x1.z()},
          Vec3<double>{x2.x(), x2.y(), x2.z()}, Vec3<double>{x3.x(), x3.y(), x3.z()}};
}

}  // namespace

double dihedral_angle(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                      const Eigen::Vector3d& x3) {
  const Eigen::Vector3d edge = x1 - x0;
  const Eigen::Vector3d normal_a = edge.cross(x2 - x0);
  const Eigen::Vector3d normal_b = (x3 - x0).cross(edge);
  return std::atan2(normal_a.cross(normal_b).dot(edge) / edge.norm(), normal_a.dot(normal_b));
}

double hinge_energy(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                    const Eigen::Vector3d& x3, double stiffness, double rest_angle) {
  const double excess = dihedral_angle(x0, x1, x2, x3) - rest_angle;
  return stiffness * excess * excess;
}

HingeElement hinge_element(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                           const Eigen::Vector3d& x3, double stiffness, double rest_angle, bool with_hessian) {
  const double excess = dihedral_angle(x0, x1, x2, x3) - rest_angle;
  HingeElement element;
  element.energy = stiffness * excess * excess;
  const std::array<Vec3<double>, 4> x = as_arrays(x0, x1, x2, x3);
  const std::array<Vec3<double>, 4> g = angle_gradient(x);
  Vector12d angle_grad;
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) angle_grad(3 * v + c) = g[v][c];
  element.gradient = 2.0 * stiffness * excess * angle_grad;
  if (!with_hessian) return element;

  // Hessian of theta: the Jacobian of angle_gradient, one forward-mode direction per coordinate.
  using Dual = Eigen::AutoDiffScalar<Vector12d>;
  std::array<Vec3<Dual>, 4> xd;
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) xd[v][c] = Dual(x[v][c], 12, 3 * v + c);
  const std::array<Vec3<Dual>, 4> gd = angle_gradient(xd);
  Matrix12d angle_hessian;
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) angle_hessian.row(3 * v + c) = gd[v][c].derivatives().transpose();
  // Symmetric up to rounding; make it exactly so.
  angle_hessian = 0.5 * (angle_hessian + angle_hessian.transpose()).eval();
  element.hessian = 2.0 * stiffness * (angle_grad * angle_grad.transpose() + excess * angle_hessian);
  return element;
}

}  // namespace physarum
