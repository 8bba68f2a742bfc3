#pragma once
// The result as a mesh file: the INPUT mesh (its own coordinates and triangles) with one float
// property per vertex (default name "pheromone") and a vertex colour from a colour map,
// in binary little-endian PLY. Written through a temporary file and renamed (atomic_write.hpp).
#include "common/color_mapping.hpp"
#include "common/element_data.hpp"
#include "common/input_mesh.hpp"

#include <optional>
#include <string>
#include <vector>

namespace physarum {

// How values become colours (levels, gamma, remap curve, colour map): common/color_mapping.hpp.
using FieldColoring = ColorMapping;

// Writes `mesh` with `values` (one per input vertex) to `path`. Header:
//   element vertex N: float x, y, z; float <property_name>; uchar red, green, blue
//   element face F: list uchar int vertex_indices
// Throws InputError (naming path) when the sizes differ or the file cannot be written; then no file
// (not even a partial one) is left at `path`.
void write_field_ply(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                     const FieldColoring& coloring = {}, const std::string& property_name = "pheromone");

}  // namespace physarum
