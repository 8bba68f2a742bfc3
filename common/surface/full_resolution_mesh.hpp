#pragma once
// The result at full resolution: the intrinsic triangulation made explicit as an ordinary mesh.
// Its vertices are the intrinsic vertices, each placed at its location on the input surface (a
// barycentric combination of the corners of the input face it lies in, in the input's own
// coordinates); its triangles are the intrinsic faces (SurfaceDomain::face_vertices). A field on the
// intrinsic vertices is then the mesh's per-vertex field with no interpolation at all, so every
// detail the simulation resolved finer than the input triangles survives in fields_full.ply and in
// the preview.
//
// It is a mesh of straight CHORDS: an intrinsic edge is a geodesic on the input surface and may
// cross input edges; drawn straight, it cuts through the surface wherever that bends (by the chord's
// sagitta). Inside a flat input face the chord is the geodesic itself.
//
// The result is an InputMesh so that the writers and the previewer take it unchanged, but it need
// not satisfy InputMesh's promises: an intrinsic triangulation may join two vertices by several
// edges, and a face may even repeat a vertex (a loop edge) or have collinear chords, which draw as
// nothing. It has no UVs (texture baking reads the input's).
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace physarum {

struct FullResolutionMesh {
  // Vertex v is intrinsic vertex v; triangle f is intrinsic face f.
  InputMesh mesh;

  // The per-vertex values of `mesh` for a field on the intrinsic vertices: the same numbers in the
  // same order (the numberings coincide by construction; this is the one place that says so).
  // InputError when the field has the wrong size.
  InputVertexData<double> vertex_values(const IntrinsicVertexData<double>& field) const;
};

// Builds the mesh described above. `input` must be the mesh the domain's vertex locations refer to,
// or one with the same triangles (e.g. PreparedSurface::input, in file coordinates, for a domain built
// on the scaled PreparedSurface::simulated). InputError when a location names a face `input` lacks.
FullResolutionMesh build_full_resolution_mesh(const InputMesh& input, const SurfaceDomain& domain);

// One intrinsic face as a chord triangle: its corners' positions on the input surface (as in the
// full-resolution mesh) and the input faces they lie in.
struct ChordTriangle {
  std::array<Eigen::Vector3d, 3> corner;
  std::array<int, 3> input_face;
};

// The chord triangle of every intrinsic face, in face order. Loops over faces that need their
// corners' positions (point location, texture baking) read these contiguously: the triangulation
// numbers vertices in insertion order, so reaching them through face_vertices jumps around memory
// (three cache misses per face at a million faces). InputError as build_full_resolution_mesh.
std::vector<ChordTriangle> chord_triangles(const InputMesh& input, const SurfaceDomain& domain);

}  // namespace physarum
