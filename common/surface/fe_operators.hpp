#pragma once
// Piecewise-linear finite elements on a triangle mesh given by edge lengths alone (intrinsic
// geometry): triangle layout and area, corner cotangents, the cotan Laplacian, lumped mass and
// per-face gradients. Everything is built face by face from halfedges, never from vertex pairs, so
// meshes with two edges between the same vertices, or self-loop edges, are handled.
//
// Conventions (IntrinsicMesh): halfedge i of face f runs from corner i to corner (i+1)%3 and has
// length l_i; corner k is opposite halfedge (k+1)%3.
#include "common/intrinsic/intrinsic_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

namespace physarum {

struct SurfaceDomain;

// Area from the three edge lengths (Kahan's numerically stable Heron formula). Returns 0 or a NaN
// when the lengths violate the triangle inequality; callers validate.
double triangle_area_from_lengths(const std::array<double, 3>& l);

// The face frame of surface_domain.hpp: corner 0 at the origin, corner 1 on +x, corner 2 above.
std::array<Eigen::Vector2d, 3> layout_triangle(const std::array<double, 3>& l);

// cot of the interior angle at corner k, k = 0, 1, 2. Needs a valid (positive-area) triangle.
std::array<double, 3> corner_cotangents(const std::array<double, 3>& l);

// Per halfedge 3f+i: the cotan weight of its edge, w = (cot a + cot b)/2 with a, b the angles
// opposite the edge in the faces on either side (cot a / 2 on a boundary edge). Both halfedges of
// an interior edge carry the same value. Negative weights mark non-Delaunay edges (Fig. 4).
std::vector<std::array<double, 3>> cotan_edge_weights(const IntrinsicMesh& mesh);

// The cotan Laplacian, positive semi-definite convention: (L u)_i = sum_j w_ij (u_i - u_j).
// Validates every face (InputError naming the face) before using its lengths.
Eigen::SparseMatrix<double, Eigen::RowMajor> cotan_laplacian(const IntrinsicMesh& mesh);

// Lumped (barycentric) mass: one third of the area of every incident face corner.
std::vector<double> lumped_mass(const IntrinsicMesh& mesh);

// Throws InputError (naming `source` and the face) when face f has a non-finite or non-positive
// edge length, violates the strict triangle inequality, or has zero area.
void validate_face_lengths(const IntrinsicMesh& mesh, int face, const char* source = "intrinsic mesh");

// Gradient, in face f's frame, of the linear function taking corner_values[k] at corner k.
Eigen::Vector2d face_gradient(const SurfaceDomain& domain, int face, const std::array<double, 3>& corner_values);

// Gradient of a per-vertex field on every face (in each face's frame).
std::vector<Eigen::Vector2d> face_gradients(const SurfaceDomain& domain, const std::vector<double>& vertex_values);

}  // namespace physarum
