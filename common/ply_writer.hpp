#pragma once
// The result as a mesh file: a mesh (the INPUT mesh in its own coordinates for pheromone.ply, the
// full-resolution mesh for fields_full.ply) with one float property per vertex for each field
// (named after it, e.g. "pheromone") and a vertex colour from a perceptual colour map applied to the
// first field, in binary little-endian PLY. Written through a temporary file and renamed
// (atomic_write.hpp).
#include "common/colormap.hpp"
#include "common/element_data.hpp"
#include "common/input_mesh.hpp"

#include <optional>
#include <string>
#include <vector>

namespace physarum {

// How values become colours: t = (value - low) / (high - low), clamped to [0, 1].
struct FieldColoring {
  Colormap map = Colormap::Viridis;
  double low = 0.0;
  std::optional<double> high;  // default: the largest value (all `low`-coloured when that is <= low)

  // The effective upper end for `values`.
  double upper(const InputVertexData<double>& values) const;
  // t in [0, 1] for one value, given the effective upper end.
  double normalise(double value, double upper_end) const;
};

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

// One field on the input mesh (pheromone.ply): write_fields_ply with the single field
// `property_name` and the description "<property_name> per input vertex".
void write_field_ply(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                     const FieldColoring& coloring = {}, const std::string& property_name = "pheromone");

}  // namespace physarum
