#pragma once
// Points and chord triangles: an intrinsic face drawn as the straight triangle through its three
// vertices' positions on the input surface (common/surface/full_resolution_mesh.hpp), the
// barycentric coordinates of a point projected onto its plane, and the nearest point of a triangle.
// Texture baking and the harness's common sampling both locate surface points on an intrinsic
// triangulation through these.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace physarum {

// A chord triangle contains a projected point when its barycentrics are >= -kChordSlack.
constexpr double kChordSlack = 1e-3;
// The containing chord triangle is accepted when the point is within this fraction of the
// triangle's longest edge from it; otherwise the nearest chord triangle is searched for.
constexpr double kAcceptableDistance = 0.05;

// The chord triangle of an intrinsic face and the barycentric coordinates of points projected onto
// its plane (Ericson, Real-Time Collision Detection 3.4).
struct Chord {
  Eigen::Vector3d a, v0, v1, unit_normal;
  double d00 = 0, d01 = 0, d11 = 0, inverse_denominator = 0;
  double longest_edge = 0;
  bool degenerate = true;

  Chord(const Eigen::Vector3d& pa, const Eigen::Vector3d& pb, const Eigen::Vector3d& pc)
      : a(pa), v0(pb - pa), v1(pc - pa) {
    d00 = v0.dot(v0);
    d01 = v0.dot(v1);
    d11 = v1.dot(v1);
    longest_edge = std::sqrt(std::max({d00, d11, (pc - pb).squaredNorm()}));
    const double denominator = d00 * d11 - d01 * d01;
    const Eigen::Vector3d n = v0.cross(v1);
    // Degenerate when the sine of the angle at a is below ~1e-6 (collinear or repeated corners).
    degenerate = !(denominator > 1e-12 * d00 * d11) || !(n.norm() > 0.0);
    if (!degenerate) {
      inverse_denominator = 1.0 / denominator;
      unit_normal = n.normalized();
    }
  }
  // Barycentric coordinates of x's projection onto the plane (for a non-degenerate chord).
  Eigen::Vector3d barycentric(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d v2 = x - a;
    const double d20 = v2.dot(v0), d21 = v2.dot(v1);
    const double b1 = (d11 * d20 - d01 * d21) * inverse_denominator;
    const double b2 = (d00 * d21 - d01 * d20) * inverse_denominator;
    return {1.0 - b1 - b2, b1, b2};
  }
  double signed_distance(const Eigen::Vector3d& x) const { return (x - a).dot(unit_normal); }
};

// The point of segment p q nearest to x, as the parameter along it.
inline double nearest_on_segment(const Eigen::Vector3d& x, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = q - p;
  const double length2 = d.squaredNorm();
  return length2 > 0.0 ? std::clamp((x - p).dot(d) / length2, 0.0, 1.0) : 0.0;
}

// The point of triangle a b c nearest to x: its barycentric coordinates (all >= 0) and squared
// distance. For a degenerate triangle, the nearest point of its three edges.
inline std::pair<Eigen::Vector3d, double> nearest_on_triangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                                                              const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                                              const Chord& chord) {
  if (!chord.degenerate) {
    const Eigen::Vector3d beta = chord.barycentric(x);
    if (beta.minCoeff() >= 0.0) {
      const double d = chord.signed_distance(x);
      return {beta, d * d};
    }
  }
  // Outside (or degenerate): the nearest point is on an edge.
  std::pair<Eigen::Vector3d, double> best{Eigen::Vector3d(1, 0, 0), HUGE_VAL};
  const std::array<const Eigen::Vector3d*, 3> corner{&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    const int f = (e + 1) % 3;
    const double s = nearest_on_segment(x, *corner[e], *corner[f]);
    const double d2 = (x - ((1.0 - s) * *corner[e] + s * *corner[f])).squaredNorm();
    if (d2 < best.second) {
      best.second = d2;
      best.first.setZero();
      best.first[e] = 1.0 - s;
      best.first[f] = s;
    }
  }
  return best;
}

}  // namespace physarum
