#pragma once
// Which intrinsic faces cover which input faces: for every input face, the intrinsic faces whose
// region on the surface may overlap it. Point location on the intrinsic triangulation (texture
// baking: "which intrinsic face holds this point of input face F?") then searches a short list per
// input face instead of the whole triangulation.
//
// An intrinsic face is a geodesic triangle on the input surface. Its vertices lie in known input
// faces (SurfaceDomain::vertex_location), but its edges may cross input edges (after flips, or when
// it spans several input faces), so it can overlap input faces holding none of its vertices. Those
// are found by a flood fill over input-face adjacency (shared edges) from the faces holding its
// vertices, keeping the faces that reach into a box the geodesic triangle provably lies in:
//   every point q of the triangle is at most max(l_ij, l_ik) from vertex i along the surface (the
//   farthest point of a flat triangle from a corner is another corner), and a straight line in
//   space is no longer than a path on the surface, so q lies in the cube of that half-width around
//   each vertex's position; the box is the intersection of the three cubes.
// The region is connected and lies in the box, so every input face it touches is reached through
// faces that touch it too: the list is complete (a superset: a face that meets the box need not
// meet the triangle).
//
// The intrinsic lengths may be in the units of a uniformly scaled copy of the mesh (PreparedSurface::
// simulated); the scale is recovered from the total areas, which an intrinsic triangulation keeps.
#include "common/surface/full_resolution_mesh.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>
#include <span>
#include <vector>

namespace physarum {

class InputFaceOverlaps {
 public:
  // `mesh` is the mesh the domain's vertex locations refer to (same triangles), in any uniform scale;
  // `chords` = chord_triangles(mesh, domain). InputError when the sizes disagree.
  InputFaceOverlaps(const InputMesh& mesh, const SurfaceDomain& domain, const std::vector<ChordTriangle>& chords);

  // The intrinsic faces that may overlap input face `input_face`, in increasing order.
  std::span<const int> of(int input_face) const {
    return {faces_.data() + first_[static_cast<size_t>(input_face)],
            faces_.data() + first_[static_cast<size_t>(input_face) + 1]};
  }
  int input_face_count() const { return static_cast<int>(first_.size()) - 1; }
  size_t pair_count() const { return faces_.size(); }
  // Intrinsic lengths times this are lengths in `mesh`'s units.
  double length_scale() const { return length_scale_; }

 private:
  std::vector<size_t> first_;  // CSR: the list of input face F is faces_[first_[F] .. first_[F+1])
  std::vector<int> faces_;
  double length_scale_ = 1.0;
};

}  // namespace physarum
