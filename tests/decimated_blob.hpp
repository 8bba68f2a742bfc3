#pragma once
// A coarse input nobody tuned the harness on: a lumpy closed surface (the built-in icosphere pushed
// in and out by a few smooth waves, so no symmetry of the sphere survives) quadric-decimated with
// OpenMesh's decimater to `faces` triangles, the kind of low-poly mesh a user brings (irregular
// triangles of very unequal size, long slivers where the surface is flat). Written as an OBJ.
#include "common/mesh/shapes.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace physarum::testing {

// Writes the decimated blob to `path`; returns its face count (`faces` or within a few of it).
inline int write_decimated_blob(const std::string& path, int faces) {
  using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
  const PolygonSoup sphere = make_shape_soup("sphere");
  Mesh mesh;
  std::vector<Mesh::VertexHandle> handles;
  for (const Eigen::Vector3d& p : sphere.positions) {
    const double r = 1.0 + 0.25 * std::sin(2.0 * p.x() + 1.0) * std::cos(3.0 * p.y()) + 0.15 * std::sin(4.0 * p.z() + 0.5) +
                     0.1 * std::cos(5.0 * p.x() * p.y());
    const Eigen::Vector3d q = r * p;
    handles.push_back(mesh.add_vertex(Mesh::Point(q.x(), q.y(), q.z())));
  }
  for (size_t f = 0; f + 1 < sphere.polygon_start.size(); ++f) {
    std::vector<Mesh::VertexHandle> corners;
    for (int k = sphere.polygon_start[f]; k < sphere.polygon_start[f + 1]; ++k)
      corners.push_back(handles[static_cast<size_t>(sphere.corner_vertex[static_cast<size_t>(k)])]);
    mesh.add_face(corners);
  }
  OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  decimater.add(quadric);
  decimater.initialize();
  decimater.decimate_to_faces(0, static_cast<size_t>(faces));
  mesh.garbage_collection();

  std::ofstream out(path);
  for (const auto& v : mesh.vertices()) {
    const Mesh::Point& p = mesh.point(v);
    out << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  }
  for (const auto& f : mesh.faces()) {
    out << "f";
    for (const auto& v : f.vertices()) out << " " << v.idx() + 1;
    out << "\n";
  }
  if (!out) throw std::runtime_error(path + ": cannot write the decimated blob");
  return static_cast<int>(mesh.n_faces());
}

}  // namespace physarum::testing
