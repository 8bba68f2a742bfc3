#pragma once
// Straight walks on an intrinsic triangulation given by halfedge twins and edge lengths, with each
// face crossed unfolded into the plane of the previous one: the geodesics of the piecewise-flat
// surface, as the intrinsic triangulation's insertion and tracing on the input need them (the
// simulation's own traces work on the SurfaceDomain instead, common/surface/trace.hpp).
#include <Eigen/Core>

#include <array>
#include <vector>

namespace physarum {
// Every straight walk on a surface (these, and the simulation's traces) is bounded by this many
// faces crossed: a walk that would need more is a failure, never an endless loop.
constexpr int kMaxTraceSteps = 1 << 16;
}  // namespace physarum

namespace physarum::unfolding {

using Eigen::Vector2d;
using Eigen::Vector3d;
using Corners = std::array<Vector2d, 3>;

// Result of a straight walk across the faces of a halfedge mesh given by twins and lengths.
struct Walk {
  enum class End { Inside, Boundary, Failed } end = End::Failed;
  int face = -1;
  Corners corners;          // of `face`, in the unfolded plane of the walk
  Vector2d point;           // end point (on the boundary edge when End::Boundary)
  Vector2d direction;       // unit direction of travel at the end
  int boundary_halfedge = -1;
};

// Walks `distance` from `point` along unit `direction`, starting in `face` laid out at `corners`
// (indexed by the face's own corner numbers). Each face crossed is unfolded into the same plane
// next to the previous one, so the path stays a straight line in that plane: this is the geodesic
// of the piecewise-flat surface. Stops at boundary edges.
Walk walk_straight(const std::vector<int>& twin, const std::vector<double>& length, int face, Corners corners,
                   Vector2d point, const Vector2d& direction, double distance);

// Layout of face f with corner `origin_corner` at the origin and the next corner on the +x axis.
Corners layout_face(const std::vector<double>& length, int f, int origin_corner);

// The angle of v from the +x axis, in (-pi, pi].
double direction_angle(const Vector2d& v);

// Barycentric coordinates with negative entries (rounding) set to 0 and renormalised.
Vector3d clamped_barycentric(Vector3d b);

}  // namespace physarum::unfolding
