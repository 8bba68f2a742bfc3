#pragma once
// The result as a mesh file: the INPUT mesh (its own coordinates and triangles) with one float
// property per vertex (default name "pheromone") and a vertex colour from a perceptual colour map,
// in binary little-endian PLY. Written through a temporary file and renamed (atomic_write.hpp).
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

// Writes `mesh` with `values` (one per input vertex) to `path`. Header:
//   element vertex N: float x, y, z; float <property_name>; uchar red, green, blue
//   element face F: list uchar int vertex_indices
// Throws InputError (naming path) when the sizes differ or the file cannot be written; then no file
// (not even a partial one) is left at `path`.
void write_field_ply(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                     const FieldColoring& coloring = {}, const std::string& property_name = "pheromone");

}  // namespace physarum
