#pragma once
// Geodesic distance by fast marching on the intrinsic (Delaunay) triangulation of a SurfaceDomain
// (Kimmel & Sethian, "Computing geodesic paths on manifolds", PNAS 1998).
//
// Vertices are accepted in order of distance (a binary heap). When a vertex is accepted, every
// not-yet-accepted corner C of its faces is updated
//   * through the triangle (C; A, B) when both other corners are accepted: the virtual source S at
//     distance d_A from A and d_B from B beyond edge AB is the point a plane wave (or, for a single
//     seed on a flat surface, the seed itself) comes from; d_C = |S - C| when the segment SC crosses
//     AB (causality), the same answer as Kimmel-Sethian's quadratic;
//   * along each edge, d_C = d_A + |AC| (Dijkstra), which is what remains when no triangle update is
//     causal.
// The triangle update is monotone only at a corner whose angle is at most 90 degrees. An obtuse
// corner C is split, once in the constructor, by unfolding the faces beyond its opposite edge into
// the plane of its triangle (intrinsic layouts from edge lengths) until a vertex D lands in the
// corner's section: the cone of directions at most 90 degrees from both CA and CB. C is then
// updated through the two virtual triangles (C; A, D) and (C; D, B), each acute at C. The unfolding
// follows the section through the strip of faces, so the segment CD lies on the surface; it gives up
// after kMaxUnfoldings faces or at a boundary, and C keeps its obtuse triangle (then only causal
// updates and edge updates reach it).
//
// Exact (up to rounding) on a flat surface for a single seed when every corner the wave passes is
// acute or split: the virtual source is then the seed itself.
#include "common/element_data.hpp"
#include "common/surface_domain.hpp"

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace physarum {

class FastMarchingGeodesics {
 public:
  static constexpr int kMaxUnfoldings = 32;

  // Finds and splits the obtuse corners. The domain must outlive this object.
  explicit FastMarchingGeodesics(const SurfaceDomain& domain);

  // Distance from the nearest of `seeds` (intrinsic vertex ids). InputError when `seeds` is empty,
  // names a vertex out of range, or misses a connected piece of the surface.
  IntrinsicVertexData<double> distance(const std::vector<int>& seeds) const;

  int obtuse_corner_count() const { return obtuse_corners_; }
  int split_corner_count() const { return split_corners_; }  // obtuse corners whose unfolding succeeded

 private:
  // A virtual triangle (target; a, b): corner positions in the frame of the face whose corner
  // 3f + k (target_corner) it splits, shifted to put the target at the origin.
  struct VirtualStencil {
    int target, target_corner, a, b;
    Eigen::Vector2d position_a, position_b;
  };
  // A tentative value with where it comes from: the corner 3f + k it was reached through, and the
  // source S - vertex in that face's frame, with the distance already travelled before S.
  struct Reach {
    double value = std::numeric_limits<double>::infinity();
    int corner = -1;  // -1: a seed
    Eigen::Vector2d source = Eigen::Vector2d::Zero();
    double offset = 0.0;
  };
  void split_obtuse_corner(int face, int corner);

  const SurfaceDomain& domain_;
  std::vector<int> vertex_face_start_, vertex_faces_;  // CSR: 3f + corner of every face at a vertex
  std::vector<char> corner_split_;                      // per 3f + k: updated through virtual stencils instead
  std::vector<char> blocking_;                          // per vertex: a saddle or on the boundary
  std::vector<VirtualStencil> stencils_;
  std::vector<int> stencil_start_, stencils_by_base_;  // CSR: stencils in which a vertex is a or b
  int obtuse_corners_ = 0, split_corners_ = 0;
};

}  // namespace physarum
