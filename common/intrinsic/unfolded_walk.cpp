#include "common/intrinsic/unfolded_walk.hpp"

#include "common/intrinsic/intrinsic_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace physarum::unfolding {

Walk walk_straight(const std::vector<int>& twin, const std::vector<double>& length, int face, Corners corners,
                   Vector2d point, const Vector2d& direction, double distance) {
  Walk walk;
  walk.direction = direction;
  double remaining = distance;
  int entry_edge = -1;
  for (int step = 0; step < kMaxTraceSteps; ++step) {
    // The exit edge: among edges the direction leaves through (positive speed along the outward
    // normal), the first one met. Edges through the start point (a vertex start) have speed <= 0
    // when the direction points into the face, so they are never taken.
    int exit_edge = -1;
    double exit_t = std::numeric_limits<double>::infinity();
    for (int j = 0; j < 3; ++j) {
      if (j == entry_edge) continue;
      const Vector2d& a = corners[j];
      const Vector2d edge = corners[(j + 1) % 3] - a;
      const Vector2d outward(edge.y(), -edge.x());
      const double speed = direction.dot(outward);
      if (speed <= 0.0) continue;
      const double t = (a - point).dot(outward) / speed;
      if (t < exit_t) {
        exit_t = t;
        exit_edge = j;
      }
    }
    walk.face = face;
    walk.corners = corners;
    if (exit_edge < 0 || std::max(exit_t, 0.0) >= remaining) {
      walk.point = point + remaining * direction;
      walk.end = Walk::End::Inside;
      return walk;
    }
    exit_t = std::max(exit_t, 0.0);
    point += exit_t * direction;
    remaining -= exit_t;
    const int h = 3 * face + exit_edge;
    const int t = twin[h];
    if (t < 0) {
      walk.point = point;
      walk.end = Walk::End::Boundary;
      walk.boundary_halfedge = h;
      return walk;
    }
    const int g = t / 3, k = t % 3;
    Corners unfolded;
    unfolded[k] = corners[(exit_edge + 1) % 3];
    unfolded[(k + 1) % 3] = corners[exit_edge];
    unfolded[(k + 2) % 3] = geometry::layout_third_corner(unfolded[k], unfolded[(k + 1) % 3], length[t],
                                                          length[3 * g + (k + 2) % 3], length[3 * g + (k + 1) % 3]);
    face = g;
    corners = unfolded;
    entry_edge = k;
  }
  walk.end = Walk::End::Failed;
  return walk;
}

// Layout of face f with corner `origin_corner` at the origin and the next corner on the +x axis.
Corners layout_face(const std::vector<double>& length, int f, int origin_corner) {
  const int i = origin_corner, j = (i + 1) % 3, k = (i + 2) % 3;
  Corners c;
  c[i] = Vector2d::Zero();
  c[j] = Vector2d(length[3 * f + i], 0.0);
  c[k] = geometry::layout_third_corner(c[i], c[j], length[3 * f + i], length[3 * f + k], length[3 * f + j]);
  return c;
}

double direction_angle(const Vector2d& v) { return std::atan2(v.y(), v.x()); }

Vector3d clamped_barycentric(Vector3d b) {
  for (int i = 0; i < 3; ++i) b[i] = std::max(b[i], 0.0);
  const double sum = b.sum();
  return sum > 0.0 ? Vector3d(b / sum) : Vector3d(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
}

}  // namespace physarum::unfolding
