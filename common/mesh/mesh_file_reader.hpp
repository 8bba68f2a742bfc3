#pragma once
// Reading a mesh file into a raw polygon soup: OpenMesh's parsers do the format work (OBJ, OFF,
// PLY, STL), but no topology is decided here. OpenMesh's own mesh classes refuse non-manifold
// input, and we want to repair such input (mesh_repair.hpp) or explain exactly what is wrong.
#include <Eigen/Core>

#include <string>
#include <vector>

namespace physarum {

// Polygons exactly as the file lists them, in flat storage: polygon p has the corners
// corner_vertex[polygon_start[p] .. polygon_start[p+1]). Indices are NOT validated: a corner may
// name a vertex the file does not have (the repair step reports it with the file name).
struct PolygonSoup {
  std::vector<Eigen::Vector3d> positions;
  std::vector<int> polygon_start{0};  // size polygon_count() + 1
  std::vector<int> corner_vertex;

  // Texture coordinates, corner-aligned with corner_vertex (corner_uv[k] indexes uvs), or both
  // empty when the file has none (or has them only for some polygons).
  std::vector<Eigen::Vector2d> uvs;
  std::vector<int> corner_uv;

  // Repairs the reader made on its own (OpenMesh's OBJ reader removes repeated corners), for the
  // user to see.
  std::vector<std::string> warnings;

  int polygon_count() const { return static_cast<int>(polygon_start.size()) - 1; }
  int polygon_size(int p) const { return polygon_start[p + 1] - polygon_start[p]; }
  void add_polygon(const std::vector<int>& vertices) {
    corner_vertex.insert(corner_vertex.end(), vertices.begin(), vertices.end());
    polygon_start.push_back(static_cast<int>(corner_vertex.size()));
  }
};

// File extensions load_mesh accepts, lower case with the dot (".obj", ...).
const std::vector<std::string>& supported_mesh_extensions();

// Reads PATH through OpenMesh's reader for its extension. Throws InputError naming the file when
// the extension is not supported, the file cannot be opened, or the reader rejects it.
PolygonSoup read_polygon_soup(const std::string& path);

// For error messages: the first number in a text mesh file that parses as NaN or infinity, as
// "line L: non-finite number 'TOKEN'", or "" when there is none (or the file is binary). The
// readers skip or misparse such numbers, so the error they lead to would otherwise be misleading.
std::string find_non_finite_number(const std::string& path);

}  // namespace physarum
