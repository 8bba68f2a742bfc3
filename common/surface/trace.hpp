#pragma once
// Straight-line (geodesic) walking across the intrinsic faces of a surface domain: the single
// traversal primitive of agents (movement) and their sensors.
#include "common/intrinsic/unfolded_walk.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>
#include <vector>

namespace physarum {

// What happens when a trace meets a boundary edge: agents reflect (mirror the heading about the
// edge and keep walking), sensors stop (the trace ends on the boundary).
enum class BoundaryRule { Reflect, Stop };

// One straight piece of a trace inside a single face, in that face's frame.
struct TraceSegment {
  int face = -1;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
};

struct TraceResult {
  int face = -1;                                         // face containing the end point
  Eigen::Vector2d position = Eigen::Vector2d::Zero();    // end point in that face's frame
  Eigen::Vector2d heading = Eigen::Vector2d::Zero();     // unit heading at the end, same frame
  double length = 0.0;        // distance walked (shorter than asked only when stopped)
  bool hit_boundary = false;  // a boundary edge was met (reflected or stopped at)
  int face_crossings = 0;     // interior edges crossed
};

// Walks `length` from `start` (in face `face`'s frame) along the unit vector `heading`. When
// `segments` is given it is cleared and receives every per-face piece, in order; their lengths add
// up to the returned length. The walk is bounded (kMaxTraceSteps pieces, common/intrinsic/unfolded_walk.hpp);
// it never leaves the surface.
TraceResult trace(const SurfaceDomain& domain, int face, const Eigen::Vector2d& start,
                  const Eigen::Vector2d& heading, double length, BoundaryRule rule,
                  std::vector<TraceSegment>* segments = nullptr);

}  // namespace physarum
