#include "common/surface/full_resolution_mesh.hpp"

#include "common/base/errors.hpp"
#include "common/base/parallel_chunks.hpp"

#include <algorithm>

#include <string>

namespace physarum {

InputVertexData<double> FullResolutionMesh::vertex_values(const IntrinsicVertexData<double>& field) const {
  if (static_cast<int>(field.size()) != mesh.vertex_count())
    throw InputError("full-resolution result of " + mesh.source + ": " + std::to_string(field.size()) +
                     " values for its " + std::to_string(mesh.vertex_count()) + " intrinsic vertices");
  return InputVertexData<double>(field.values());
}

FullResolutionMesh build_full_resolution_mesh(const InputMesh& input, const SurfaceDomain& domain) {
  FullResolutionMesh full;
  InputMesh& mesh = full.mesh;
  mesh.source = input.source + " (full resolution)";
  mesh.positions.resize(static_cast<size_t>(domain.vertex_count));
  for (int v = 0; v < domain.vertex_count; ++v) {
    const SurfacePoint& p = domain.vertex_location[static_cast<size_t>(v)];
    if (p.face < 0 || p.face >= input.triangle_count())
      throw InputError("full-resolution result: intrinsic vertex " + std::to_string(v) + " lies on input face " +
                       std::to_string(p.face) + ", which " + input.source + " does not have");
    const auto& t = input.triangles[static_cast<size_t>(p.face)];
    mesh.positions[static_cast<size_t>(v)] = p.barycentric[0] * input.positions[t[0]] +
                                             p.barycentric[1] * input.positions[t[1]] +
                                             p.barycentric[2] * input.positions[t[2]];
  }
  mesh.triangles = domain.face_vertices;
  // No file behind these vertices: each is its own "file vertex", as for shapes.
  mesh.file_vertex.resize(static_cast<size_t>(domain.vertex_count));
  for (int v = 0; v < domain.vertex_count; ++v) mesh.file_vertex[static_cast<size_t>(v)] = v;
  return full;
}

std::vector<ChordTriangle> chord_triangles(const InputMesh& input, const SurfaceDomain& domain) {
  const std::vector<Eigen::Vector3d> positions = build_full_resolution_mesh(input, domain).mesh.positions;
  std::vector<ChordTriangle> chords(static_cast<size_t>(domain.face_count));
  const int chunks = std::max(1, std::min(64, domain.face_count / 16384));
  parallel_chunks(chunks, [&](int chunk) {
    const int begin = static_cast<int>(static_cast<long long>(domain.face_count) * chunk / chunks);
    const int end = static_cast<int>(static_cast<long long>(domain.face_count) * (chunk + 1) / chunks);
    for (int f = begin; f < end; ++f) {
      const auto& v = domain.face_vertices[static_cast<size_t>(f)];
      ChordTriangle& chord = chords[static_cast<size_t>(f)];
      for (int c = 0; c < 3; ++c) {
        chord.corner[c] = positions[static_cast<size_t>(v[c])];
        chord.input_face[c] = domain.vertex_location[static_cast<size_t>(v[c])].face;
      }
    }
  });
  return chords;
}

}  // namespace physarum
