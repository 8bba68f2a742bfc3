#pragma once
// A snapshot of an intrinsic triangulation in compact, index-based form: what the surface domain,
// the FE operators and the tests consume. Halfedge h = 3*f + i runs from faces[f][i] to
// faces[f][(i+1)%3]. Intrinsic triangulations may contain faces that share two edges, or an edge
// whose two ends are the same vertex, so adjacency is stored per halfedge, never by vertex pair.
#include "common/mesh/surface_point.hpp"

#include <array>
#include <vector>

namespace physarum {

struct IntrinsicMesh {
  int vertex_count = 0;
  std::vector<std::array<int, 3>> faces;            // vertex ids, counter-clockwise
  std::vector<std::array<double, 3>> edge_lengths;  // [f][i]: length of halfedge 3f+i
  std::vector<std::array<int, 3>> twin;             // [f][i]: opposite halfedge 3g+j, or -1 on a boundary
  std::vector<SurfacePoint> vertex_location;        // where each intrinsic vertex sits on the input mesh

  int face_count() const { return static_cast<int>(faces.size()); }
};

// Builds the intrinsic mesh of an input mesh as it is (extrinsic edge lengths, no flips); vertex
// locations are the input vertices themselves.
struct InputMesh;
IntrinsicMesh intrinsic_mesh_from_input(const InputMesh& mesh);

}  // namespace physarum
