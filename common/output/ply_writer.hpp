#pragma once
// The result as a mesh file: a mesh (the INPUT mesh in its own coordinates for pheromone.ply, the
// full-resolution mesh for fields_full.ply) with one float property per vertex for each field
// (named after it, e.g. "pheromone") and a vertex colour from a colour map applied to the
// first field, in binary little-endian PLY. Written through a temporary file and renamed
// (atomic_write.hpp).
#include "common/color/color_mapping.hpp"
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"

#include <optional>
#include <string>
#include <vector>

namespace physarum {

// How values become colours (levels, gamma, remap curve, colour map): common/color/color_mapping.hpp.
using FieldColoring = ColorMapping;

// One named per-vertex field of a mesh being written. The values are referenced, not copied (a
// full-resolution field can have millions), so they must outlive the write call.
struct PlyField {
  std::string name;  // the PLY property name: letters, digits, '_' and '-', not x/y/z/red/green/blue
  const InputVertexData<double>& values;
};

// Writes `mesh` with `fields` (at least one; one value per mesh vertex each) to `path`. Header:
//   comment physarum: <description>
//   element vertex N: float x, y, z; float <name> for each field in order; uchar red, green, blue
//   element face F: list uchar int vertex_indices
// The colours are fields[0] through `coloring`. Throws InputError (naming path) when a size differs,
// a name is not a usable property name or is repeated, or the file cannot be written; then no file
// (not even a partial one) is left at `path`.
void write_fields_ply(const std::string& path, const InputMesh& mesh, const std::vector<PlyField>& fields,
                      const FieldColoring& coloring, const std::string& description);

// One named per-face value of a mesh being written (one per triangle, in triangle order); referenced
// like PlyField.
struct PlyFaceField {
  std::string name;  // the same rules as PlyField's names
  const std::vector<double>& values;
};

// Properties of vertices and of faces (maps.ply: a scene's scalar maps per vertex, its vector maps'
// components per face). As write_fields_ply, with after the face's vertex_indices one
//   property float <name>
// per face field, and vertex colours (from vertex_fields[0] through `coloring`) only when there is
// a vertex field. At least one field of either kind; names are unique across both.
void write_fields_ply(const std::string& path, const InputMesh& mesh, const std::vector<PlyField>& vertex_fields,
                      const std::vector<PlyFaceField>& face_fields, const FieldColoring& coloring,
                      const std::string& description);

// One field on the input mesh (pheromone.ply): write_fields_ply with the single field
// `property_name` and the description "<property_name> per input vertex".
void write_field_ply(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                     const FieldColoring& coloring = {}, const std::string& property_name = "pheromone");

}  // namespace physarum
