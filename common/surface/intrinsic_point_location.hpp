#pragma once
// Where a point of the input surface lies on an intrinsic triangulation of that surface: the
// intrinsic face holding it and its barycentric coordinates there, so that a field on the
// triangulation's vertices can be read at any point of the surface the way the discretisation
// defines it (linear in each intrinsic triangle).
//
// How (the method texture baking uses, common/output/texture_bake.hpp, for one point at a time): the
// point lies in a known input face F (a SurfacePoint: an intrinsic vertex's location, for instance);
// the intrinsic faces that may overlap F are listed by InputFaceOverlaps; each is drawn as its chord
// triangle (common/surface/chord_geometry.hpp) and the point projected onto its plane; the containing
// chord triangle nearest to the point wins, and when none contains it within kAcceptableDistance of
// its size (rounding at an edge, a strongly bent face) the nearest chord triangle is taken at its
// nearest point. Exact in flat parts of the surface (an intrinsic face there IS its chord triangle);
// elsewhere within the face's sagitta of the point, which vanishes as the triangulation is refined.
// An input vertex is an intrinsic vertex of every intrinsic triangulation of its mesh, so a point at
// an input vertex reads that vertex's value exactly.
#include "common/mesh/input_mesh.hpp"
#include "common/mesh/surface_point.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/surface/input_face_overlaps.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace physarum {

struct IntrinsicLocation {
  int face = -1;                                         // intrinsic face
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // in that face, >= 0, summing to 1
};

class IntrinsicPointLocator {
 public:
  // `mesh` is the mesh the domain's vertex locations refer to (same triangles, any uniform scale).
  IntrinsicPointLocator(const InputMesh& mesh, const SurfaceDomain& domain);

  // The intrinsic face holding `point` (a point of `mesh`), as described above. InputError when the
  // point names a face the mesh lacks.
  IntrinsicLocation locate(const SurfacePoint& point) const;

 private:
  const InputMesh& mesh_;
  std::vector<ChordTriangle> chords_;
  InputFaceOverlaps overlaps_;
};

// The linear interpolation of a field on `domain`'s vertices at `points` (on `mesh`, as above): a
// sparse matrix with one row per point and one column per intrinsic vertex, at most three entries a
// row, each row summing to 1 (a point at an input vertex has the single entry 1).
Eigen::SparseMatrix<double, Eigen::RowMajor> interpolation_at_points(const InputMesh& mesh, const SurfaceDomain& domain,
                                                                     const std::vector<SurfacePoint>& points);

}  // namespace physarum
