#pragma once
// Moving per-vertex fields between the input mesh and the intrinsic triangulation: the one place
// where values change numbering (common/base/element_data.hpp).
//
// Intrinsic -> input: an intrinsic triangulation keeps every input vertex (flips and insertions
// never remove one), so each input vertex IS an intrinsic vertex and its value is read directly, no
// interpolation. Our IntrinsicTriangulation also keeps their indices (intrinsic vertices
// 0..nV_input-1 are the input vertices, inserted ones come after); input_vertex_to_intrinsic checks
// that cheaply and, should a triangulation ever renumber, finds each input vertex from the
// intrinsic vertices' locations instead, so the transfer never depends on the numbering.
//
// Input -> intrinsic (parameter maps painted on the input): each intrinsic vertex sits at a
// SurfacePoint of the input mesh; the input field is interpolated linearly there.
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/mesh/surface_point.hpp"

#include <vector>

namespace physarum {

// For each input vertex, the intrinsic vertex sitting on it. `intrinsic_locations` is one
// SurfacePoint (on the input mesh) per intrinsic vertex, e.g. SurfaceDomain::vertex_location.
// Throws InputError when some input vertex has no intrinsic vertex on it.
InputVertexData<int> input_vertex_to_intrinsic(const InputMesh& input,
                                               const IntrinsicVertexData<SurfacePoint>& intrinsic_locations);

// Values at the input vertices from values at the intrinsic vertices.
InputVertexData<double> intrinsic_to_input(const InputMesh& input,
                                           const IntrinsicVertexData<SurfacePoint>& intrinsic_locations,
                                           const IntrinsicVertexData<double>& intrinsic_values);
// Same with a map from input_vertex_to_intrinsic computed once (cheap per frame).
InputVertexData<double> intrinsic_to_input(const InputVertexData<int>& input_to_intrinsic_map,
                                           const IntrinsicVertexData<double>& intrinsic_values);

// Values at the intrinsic vertices: the input's per-vertex field interpolated linearly (barycentric)
// at each intrinsic vertex's location.
IntrinsicVertexData<double> input_to_intrinsic(const InputMesh& input,
                                               const IntrinsicVertexData<SurfacePoint>& intrinsic_locations,
                                               const InputVertexData<double>& input_values);

}  // namespace physarum
