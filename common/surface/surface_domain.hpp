#pragma once
// The surface domain: the flat arrays both simulation backends consume (the contract between
// common/ and the backends: the reference reads them as they are, the OpenCL backend builds its
// device buffers from them alone). Built once from an intrinsic triangulation; nothing in a backend recomputes geometry.
//
// Frames: every intrinsic face has its own 2D coordinate frame, laid out from its edge lengths with
// corner 0 at the origin, corner 1 on the positive x axis and corner 2 above it (counter-clockwise).
// Halfedge h = 3*f + i is the edge of face f from corner i to corner (i+1)%3.
#include "common/base/alias_table.hpp"
#include "common/numerics/csr_matrix.hpp"
#include "common/base/element_data.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/mesh/surface_point.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace physarum {

// The rotation that carries directions from one face's frame into a neighbour's: a walk that crosses
// an edge keeps its direction by it, and rebuilds its position from the neighbour's own corners (so
// no translation is needed).
struct Rotation2 {
  double cos_angle = 1.0, sin_angle = 0.0;

  Eigen::Vector2d apply_direction(const Eigen::Vector2d& d) const {
    return {cos_angle * d.x() - sin_angle * d.y(), sin_angle * d.x() + cos_angle * d.y()};
  }
};

struct SurfaceDomain {
  int vertex_count = 0;
  int face_count = 0;
  double total_area = 0.0;

  // ---- per face ----
  std::vector<std::array<int, 3>> face_vertices;
  std::vector<std::array<Eigen::Vector2d, 3>> face_corners;  // the 2D layout described above
  IntrinsicFaceData<double> face_area;
  std::vector<std::array<int, 3>> face_neighbour;  // face across halfedge 3f+i, or -1 on a boundary
  std::vector<std::array<int, 3>> neighbour_edge;  // index j of that edge in the neighbour (twin = 3g+j)

  // ---- per halfedge (3f+i) ----
  // Maps directions from face f's frame into the frame of the face across edge i.
  // Identity on boundary edges.
  std::vector<Rotation2> edge_transition;

  // ---- per vertex ----
  IntrinsicVertexData<double> vertex_mass;            // lumped mass: one third of the incident face areas
  IntrinsicVertexData<SurfacePoint> vertex_location;  // on the input mesh, for transferring fields

  // ---- operators ----
  // Cotan Laplacian L (positive semi-definite convention: (L u)_i = sum_j w_ij (u_i - u_j),
  // w_ij = (cot a + cot b)/2), so du/dt = -D M^-1 L u is diffusion. Rows sum to zero.
  CsrMatrix laplacian;

  // Area-weighted sampler over faces (weights = area x optional per-face weight).
  AliasTable face_sampler;
};

// Builds every array above. face_weight (optional, one per face, >= 0) multiplies the face areas in
// the alias table; pass an empty vector for pure area weighting.
SurfaceDomain build_surface_domain(const IntrinsicMesh& mesh, const IntrinsicFaceData<double>& face_weight = {});

// Barycentric coordinates of a point given in face f's frame.
Eigen::Vector3d barycentric_in_face(const SurfaceDomain& domain, int face, const Eigen::Vector2d& point);

}  // namespace physarum
