#include "common/intrinsic/intrinsic_mesh.hpp"

#include "common/base/errors.hpp"
#include "common/mesh/input_mesh.hpp"

#include <string>
#include <unordered_map>

namespace physarum {

IntrinsicMesh intrinsic_mesh_from_input(const InputMesh& mesh) {
  IntrinsicMesh out;
  out.vertex_count = mesh.vertex_count();
  const int nf = mesh.triangle_count();
  out.faces = mesh.triangles;
  out.edge_lengths.resize(nf);
  out.twin.assign(nf, {-1, -1, -1});
  out.vertex_location.resize(out.vertex_count);

  // The input is manifold, so a directed edge (a, b) occurs at most once and its twin is (b, a).
  std::unordered_map<long long, int> halfedge_of;
  halfedge_of.reserve(3 * static_cast<size_t>(nf));
  auto key = [](int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); };
  for (int f = 0; f < nf; ++f) {
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.triangles[f][i], b = mesh.triangles[f][(i + 1) % 3];
      out.edge_lengths[f][i] = (mesh.positions[b] - mesh.positions[a]).norm();
      if (!halfedge_of.emplace(key(a, b), 3 * f + i).second)
        throw InputError(mesh.source + ": directed edge " + std::to_string(a) + "->" + std::to_string(b) +
                         " occurs twice (the mesh is not manifold or not consistently oriented)");
    }
  }
  for (int f = 0; f < nf; ++f) {
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.triangles[f][i], b = mesh.triangles[f][(i + 1) % 3];
      auto it = halfedge_of.find(key(b, a));
      if (it != halfedge_of.end()) out.twin[f][i] = it->second;
    }
  }
  // Each input vertex sits at the corner of some triangle that uses it.
  for (int f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i) {
      SurfacePoint& p = out.vertex_location[mesh.triangles[f][i]];
      if (p.face < 0) {
        p.face = f;
        p.barycentric = Eigen::Vector3d::Zero();
        p.barycentric[i] = 1.0;
      }
    }
  return out;
}

}  // namespace physarum
