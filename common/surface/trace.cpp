#include "common/surface/trace.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {

namespace {

// Barycentric coordinates of a point, and their rates of change along a direction, in a face frame
// (corner 0 at the origin, corner 1 on +x): a 2x2 triangular solve, no square roots.
struct FaceCoordinates {
  double inv_x1, c2x, inv_y2;
  explicit FaceCoordinates(const std::array<Eigen::Vector2d, 3>& c)
      : inv_x1(1.0 / c[1].x()), c2x(c[2].x()), inv_y2(1.0 / c[2].y()) {}
  std::array<double, 3> point(const Eigen::Vector2d& p) const {
    const double b2 = p.y() * inv_y2;
    const double b1 = (p.x() - b2 * c2x) * inv_x1;
    return {1.0 - b1 - b2, b1, b2};
  }
  std::array<double, 3> direction(const Eigen::Vector2d& d) const {
    const double db2 = d.y() * inv_y2;
    const double db1 = (d.x() - db2 * c2x) * inv_x1;
    return {-db1 - db2, db1, db2};
  }
};

// Moves a point that rounding left marginally outside its face back onto it (clamp the barycentric
// coordinates at zero and renormalise), so every trace ends inside its end face.
Eigen::Vector2d clamp_into_face(const std::array<Eigen::Vector2d, 3>& c, const FaceCoordinates& frame,
                                const Eigen::Vector2d& p) {
  std::array<double, 3> b = frame.point(p);
  if (b[0] >= 0.0 && b[1] >= 0.0 && b[2] >= 0.0 && std::isfinite(b[0] + b[1] + b[2])) return p;
  double sum = 0.0;
  for (double& x : b) {
    x = std::isfinite(x) ? std::max(x, 0.0) : 0.0;
    sum += x;
  }
  if (!(sum > 0.0)) return (c[0] + c[1] + c[2]) / 3.0;  // nothing usable: the centroid
  return (b[1] * c[1] + b[2] * c[2] + b[0] * c[0]) / sum;
}

// Directions within this relative tolerance of parallel to an edge do not cross it: a walk exactly
// along an edge continues to the edge's end instead of grazing across it at every step.
constexpr double kParallelTolerance = 1e-12;

// Where a walk from barycentric coordinates b in direction db (their change per unit length) leaves
// the face: the length to the exit and the coordinate that vanishes there (coordinate k vanishes on
// edge (k+1)%3), or corner -1 when no edge lies ahead. The walk leaves where a decreasing coordinate
// reaches zero; slightly negative coordinates (points on an edge) count as zero, and the edge it
// came in through (entry_edge, -1 for none) is never an exit at length 0.
struct FaceExit {
  double length = std::numeric_limits<double>::infinity();
  int corner = -1;
};

FaceExit face_exit(const std::array<double, 3>& b, const std::array<double, 3>& db, int entry_edge) {
  const double parallel = -kParallelTolerance * (std::abs(db[0]) + std::abs(db[1]) + std::abs(db[2]));
  FaceExit exit;
  for (int k = 0; k < 3; ++k) {
    if ((k + 1) % 3 == entry_edge || !(db[k] < parallel)) continue;
    const double t = std::max(b[k], 0.0) / -db[k];
    if (t < exit.length) {
      exit.length = t;
      exit.corner = k;
    }
  }
  if (exit.corner < 0 && entry_edge >= 0) {
    // Only the entry edge lies ahead: rounding made a heading parallel to it look like it points
    // back. Crossing back is still a valid move (the step bound caps any ping-pong).
    const int k = (entry_edge + 2) % 3;
    if (db[k] < 0.0) {
      exit.length = std::max(b[k], 0.0) / -db[k];
      exit.corner = k;
    }
  }
  return exit;
}

// The exit point on edge e (corner e to corner e+1) as a fraction along it, from the two coordinates
// that survive there at length t: it lies exactly on the edge, whatever rounding did to the point.
double fraction_along_edge(const std::array<double, 3>& b, const std::array<double, 3>& db, double t, int e) {
  const int e_next = (e + 1) % 3;
  const double weight_from = std::max(b[e] + t * db[e], 0.0);
  const double weight_to = std::max(b[e_next] + t * db[e_next], 0.0);
  const double total = weight_from + weight_to;
  return total > 0.0 ? std::clamp(weight_to / total, 0.0, 1.0) : 0.5;
}

}  // namespace

TraceResult trace(const SurfaceDomain& domain, int face, const Eigen::Vector2d& start, const Eigen::Vector2d& heading,
                  double length, BoundaryRule rule, std::vector<TraceSegment>* segments) {
  if (segments) segments->clear();

  TraceResult result;
  const double heading_norm = heading.norm();
  Eigen::Vector2d d = (heading_norm > 0.0 && std::isfinite(heading_norm)) ? Eigen::Vector2d(heading / heading_norm)
                                                                             : Eigen::Vector2d(1.0, 0.0);
  int f = face;
  Eigen::Vector2d p = start;
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) p = Eigen::Vector2d::Zero();  // clamped below
  double remaining = (length > 0.0 && std::isfinite(length)) ? length : 0.0;
  double travelled = 0.0;
  int entry_edge = -1;  // the edge we came in through (or reflected off): never an exit at t = 0

  for (int step = 0; step < kMaxTraceSteps; ++step) {
    const std::array<Eigen::Vector2d, 3>& c = domain.face_corners[f];
    const FaceCoordinates frame(c);
    const std::array<double, 3> b = frame.point(p);
    const std::array<double, 3> db = frame.direction(d);

    const auto [t_exit, corner_exit] = face_exit(b, db, entry_edge);

    if (corner_exit < 0 || t_exit >= remaining) {
      const Eigen::Vector2d end = clamp_into_face(c, frame, p + remaining * d);
      if (segments) segments->push_back({f, p, end});
      result.face = f;
      result.position = end;
      result.heading = d;
      // The whole length was walked: report it exactly rather than a sum with rounding in it.
      result.length = length > 0.0 && std::isfinite(length) ? length : 0.0;
      return result;
    }

    // Exit point on edge e (corner e to corner e+1), as a fraction s along it.
    const int e = (corner_exit + 1) % 3;
    const int e_next = (e + 1) % 3;
    const double s = fraction_along_edge(b, db, t_exit, e);
    const Eigen::Vector2d exit_point = (1.0 - s) * c[e] + s * c[e_next];
    if (segments && t_exit > 0.0) segments->push_back({f, p, exit_point});
    travelled += t_exit;
    remaining -= t_exit;

    const int g = domain.face_neighbour[f][e];
    if (g < 0) {
      result.hit_boundary = true;
      if (rule == BoundaryRule::Stop) {
        if (segments && t_exit == 0.0) segments->push_back({f, p, exit_point});
        result.face = f;
        result.position = exit_point;
        result.heading = d;
        result.length = std::min(travelled, length);
        return result;
      }
      // Mirror the heading about the edge line and keep walking inside the same face.
      const Eigen::Vector2d u = (c[e_next] - c[e]).normalized();
      d = (2.0 * d.dot(u)) * u - d;
      d.normalize();
      p = exit_point;
      entry_edge = e;
      continue;
    }

    // Cross into g. The point is rebuilt from g's own corners (the edge runs backwards there), so it
    // lies exactly on the shared edge in g's frame too; only the heading goes through the rotation.
    const int j = domain.neighbour_edge[f][e];
    const std::array<Eigen::Vector2d, 3>& cg = domain.face_corners[g];
    p = (1.0 - s) * cg[(j + 1) % 3] + s * cg[j];
    d = domain.edge_transition[3 * f + e].apply_direction(d);
    f = g;
    entry_edge = j;
    ++result.face_crossings;
  }

  // Step bound reached (only on pathological input): end where the walk got to.
  const std::array<Eigen::Vector2d, 3>& c = domain.face_corners[f];
  const Eigen::Vector2d end = clamp_into_face(c, FaceCoordinates(c), p);
  if (segments) segments->push_back({f, p, end});
  result.face = f;
  result.position = end;
  result.heading = d;
  result.length = travelled;
  return result;
}

}  // namespace physarum
