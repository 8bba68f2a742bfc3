#pragma once
// Elementary formulas on a triangle known only by its three edge lengths (the intrinsic view), and
// on 2D layouts of such triangles. Everything here is numerically careful on purpose: intrinsic
// triangulations routinely contain needles and near-degenerate triangles.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace physarum::geometry {

// Triangle area from edge lengths by Kahan's rearrangement of Heron's formula, which stays accurate
// for needles where the textbook form cancels catastrophically. Returns 0 for lengths that violate
// the triangle inequality (numerically degenerate triangles) instead of NaN.
inline double triangle_area(double a, double b, double c) {
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);  // now a >= b >= c
  const double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return product > 0.0 ? 0.25 * std::sqrt(product) : 0.0;
}

// Angle between the sides of lengths a and b, opposite the side of length c (law of cosines, the
// cosine clamped to [-1, 1] so rounding never produces NaN).
inline double corner_angle(double a, double b, double c) {
  const double cosine = (a * a + b * b - c * c) / (2.0 * a * b);
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

// Cotangent of the angle opposite side c: (a^2 + b^2 - c^2) / (4 area). A degenerate triangle gets
// a huge finite value of the right sign rather than an infinity, so sums stay comparable.
inline double cotan_opposite(double a, double b, double c) {
  const double area = triangle_area(a, b, c);
  const double numerator = a * a + b * b - c * c;
  const double denominator = std::max(4.0 * area, 1e-300 + 1e-30 * std::abs(numerator));
  return numerator / denominator;
}

inline double circumradius(double a, double b, double c) {
  const double area = triangle_area(a, b, c);
  if (area <= 0.0) return std::numeric_limits<double>::infinity();
  return a * b * c / (4.0 * area);
}

// Third corner C of a counter-clockwise triangle (A, B, C) with |AC| = length_ac and
// |BC| = length_bc, where |AB| = length_ab (given separately so the layout uses the stored edge
// length rather than a drifted distance between unfolded points).
inline Eigen::Vector2d layout_third_corner(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double length_ab,
                                           double length_ac, double length_bc) {
  const Eigen::Vector2d along = (b - a).normalized();
  const Eigen::Vector2d left(-along.y(), along.x());
  const double x = (length_ac * length_ac - length_bc * length_bc + length_ab * length_ab) / (2.0 * length_ab);
  const double y = std::sqrt(std::max(0.0, length_ac * length_ac - x * x));
  return a + x * along + y * left;
}

// Twice the signed area of the 2D triangle (a, b, c): positive when counter-clockwise.
inline double signed_area2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Barycentric coordinates of p in the 2D triangle (a, b, c).
inline Eigen::Vector3d barycentric(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                                   const Eigen::Vector2d& p) {
  const double total = signed_area2(a, b, c);
  if (total == 0.0) return Eigen::Vector3d(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
  return Eigen::Vector3d(signed_area2(p, b, c) / total, signed_area2(a, p, c) / total, signed_area2(a, b, p) / total);
}

// Circumcenter of the 2D triangle (a, b, c).
inline Eigen::Vector2d circumcenter(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a, ac = c - a;
  const double d = 2.0 * (ab.x() * ac.y() - ab.y() * ac.x());
  const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm();
  return a + Eigen::Vector2d(ac.y() * ab2 - ab.y() * ac2, ab.x() * ac2 - ac.x() * ab2) / d;
}

// Angle in [0, 2 pi).
inline double wrap_angle(double angle) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  angle = std::fmod(angle, two_pi);
  if (angle < 0.0) angle += two_pi;
  return angle >= two_pi ? 0.0 : angle;
}

}  // namespace physarum::geometry
