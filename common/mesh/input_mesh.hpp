#pragma once
// The input surface as the user gave it, after loading, triangulation and repair: a consistently
// oriented, edge-manifold, vertex-manifold triangle mesh (several components and boundaries are
// fine). Everything downstream (the intrinsic triangulation, the transfer of results back onto the
// input, texture baking) reads this and only this.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace physarum {

struct InputMesh {
  std::string source;  // file path or "shape:NAME", for messages

  std::vector<Eigen::Vector3d> positions;
  // Triangles as vertex indices, counter-clockwise seen from outside; every edge has at most two
  // incident triangles, with opposite orientations; every vertex has a single fan.
  std::vector<std::array<int, 3>> triangles;

  // Optional texture coordinates: triangle_uvs[t][c] indexes uvs for corner c of triangle t.
  // Both empty when the input has none.
  std::vector<Eigen::Vector2d> uvs;
  std::vector<std::array<int, 3>> triangle_uvs;

  // For each vertex, its index in the file as read (before unreferenced vertices were dropped and
  // non-manifold vertices were split; split copies share an index). Identity for shapes.
  std::vector<int> file_vertex;

  int split_vertices = 0;        // non-manifold vertices that were split into several
  int dropped_unreferenced = 0;  // file vertices used by no face
  int triangulated_polygons = 0; // faces with more than three corners that were triangulated
  std::vector<std::string> warnings;  // human-readable, printed by the command line

  int vertex_count() const { return static_cast<int>(positions.size()); }
  int triangle_count() const { return static_cast<int>(triangles.size()); }
};

// Topological and metric summary for `physarum mesh`.
struct InputMeshStatistics {
  int vertices = 0;
  int faces = 0;
  int edges = 0;
  int components = 0;
  int genus = 0;           // sum over components of (2 - chi_c - b_c) / 2
  int boundary_loops = 0;
  double area = 0.0;
  double bounding_box_diagonal = 0.0;
};

InputMeshStatistics compute_statistics(const InputMesh& mesh);

// Length of the diagonal of the axis-aligned box around the mesh's positions (0 without vertices):
// the scale that relative refinement sizes are given against.
double bounding_box_diagonal(const InputMesh& mesh);

}  // namespace physarum
