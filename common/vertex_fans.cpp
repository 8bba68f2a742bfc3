#include "common/vertex_fans.hpp"

#include <cmath>

namespace physarum {
namespace {

// The neighbouring corner at the same vertex across the corner's clockwise edge (to corner k+1) or
// counter-clockwise edge (from corner k+2), as 3g + j; -1 at a boundary. Halfedge i of a face runs
// from corner i to corner i+1, and the twin of halfedge i runs the other way in the neighbour.
int clockwise_corner(const SurfaceDomain& d, int face_corner) {
  const int f = face_corner / 3, k = face_corner % 3;
  const int g = d.face_neighbour[f][k];
  return g < 0 ? -1 : 3 * g + (d.neighbour_edge[f][k] + 1) % 3;
}

int counter_clockwise_corner(const SurfaceDomain& d, int face_corner) {
  const int f = face_corner / 3, k = face_corner % 3;
  const int g = d.face_neighbour[f][(k + 2) % 3];
  return g < 0 ? -1 : 3 * g + d.neighbour_edge[f][(k + 2) % 3];
}

}  // namespace

VertexFans::VertexFans(const SurfaceDomain& domain) {
  const int corner_count = 3 * domain.face_count;
  corners_.assign(static_cast<size_t>(corner_count), Corner{});
  for (int first = 0; first < corner_count; ++first) {
    if (corners_[static_cast<size_t>(first)].fan >= 0) continue;
    // Back up clockwise to the boundary, if there is one, so an open fan starts at its first edge.
    // A walk longer than the number of corners means inconsistent twins; it then just starts here.
    int start = first;
    bool closed = false;
    for (int steps = 0; steps < corner_count; ++steps) {
      const int previous = clockwise_corner(domain, start);
      if (previous < 0) break;
      if (previous == first) {
        closed = true;
        start = first;
        break;
      }
      start = previous;
    }
    const int id = static_cast<int>(fans_.size());
    double angle = 0.0;
    for (int c = start, steps = 0; c >= 0 && corners_[static_cast<size_t>(c)].fan < 0 && steps < corner_count; ++steps) {
      const int f = c / 3, k = c % 3;
      const auto& p = domain.face_corners[f];
      const Eigen::Vector2d to_next = p[(k + 1) % 3] - p[k], to_previous = p[(k + 2) % 3] - p[k];
      Corner& corner = corners_[static_cast<size_t>(c)];
      corner.fan = id;
      corner.start = angle;
      corner.angle = std::atan2(to_next.x() * to_previous.y() - to_next.y() * to_previous.x(), to_next.dot(to_previous));
      // to_fan = rotation by (start - direction of to_next).
      const double edge_direction = std::atan2(to_next.y(), to_next.x());
      corner.to_fan = Rotation2{std::cos(angle - edge_direction), std::sin(angle - edge_direction)};
      angle += corner.angle;
      c = counter_clockwise_corner(domain, c);
    }
    fans_.push_back(Fan{angle, closed, Rotation2{std::cos(angle), std::sin(angle)}});
  }
}

}  // namespace physarum
