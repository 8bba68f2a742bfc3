#pragma once
// Geodesic distance by fast marching on the intrinsic (Delaunay) triangulation of a SurfaceDomain
// (Kimmel & Sethian, "Computing geodesic paths on manifolds", PNAS 1998).
//
// Vertices are accepted in order of distance (a binary heap). Every tentative value remembers its
// source: a point S in the frame of the face it came through, with the distance travelled before S
// (the offset). When a vertex V is accepted, every not-yet-accepted corner C of its faces is offered
//   * the straight line from V's source (source tracking, after Surazhsky et al., "Fast exact and
//     approximate geodesics on meshes", SIGGRAPH 2005, approximate variant): S is unfolded round V,
//     face by face across the edges at V, into C's face, and offset + |S' - C| counts when the
//     segment enters that face across its edge at V without passing a saddle or boundary vertex on
//     its far side. This carries the true source from face to face, so on a convex polyhedron the
//     distances come close to the polyhedron's own geodesics instead of a chain of per-triangle
//     reconstructions. Only sources of paths are unfolded (an estimate's virtual source below is
//     no point a path starts from). Approximate: a source is also used for lines that enter V's
//     star away from where its own line came in, where the faces behind may differ (on spot a
//     value up to 0.18 % of the diameter below the straight line through space);
//   * along each edge, d_C = d_V + |VC| (Dijkstra): a path that bends at V, with S = V, offset d_V;
//   * through the triangle (C; V, B) when B is accepted too, an estimate: the virtual source S at
//     distance d_V from V and d_B from B beyond edge VB; d_C = |S - C| when the segment SC crosses
//     VB (causality), Kimmel-Sethian's quadratic. A point source is all one triangle can reconstruct,
//     and it undershoots where fronts converge (past the equator of a sphere: 1-1.3 % of pi at
//     icosphere level 4), so estimates count only until a tracked straight line reaches the vertex.
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
// acute or split: the source is then the seed itself. On the unit icosphere within 0.2 % of pi of the
// great circles at level 4 (h = 0.075), 0.06 % at level 6.
#include "common/base/element_data.hpp"
#include "common/surface/surface_domain.hpp"

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
