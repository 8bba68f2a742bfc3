#pragma once
// A quick look at a result: the INPUT surface seen from a fixed three-quarter view (y up, fitted to
// the bounding box), coloured by a per-vertex field through a perceptual colour map, Lambert-shaded,
// drawn by a small software rasteriser with a z-buffer and written as PNG (OpenImageIO) through a
// temporary file and rename.
#include "common/color/layer_colours.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/output/ply_writer.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace physarum {

struct PreviewOptions {
  int width = 800;
  int height = 600;
  FieldColoring coloring;                           // value -> colour, as for the PLY
  std::array<std::uint8_t, 3> background = {255, 255, 255};
  double azimuth_deg = 35.0;    // camera around the y axis, from +z towards +x
  double elevation_deg = 25.0;  // camera above the x-z plane
};

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // row-major, top row first, 3 bytes per pixel
};

// Renders `mesh` coloured by `values` (one per input vertex). InputError on a size mismatch or a
// size outside 1..16384.
RgbImage render_preview(const InputMesh& mesh, const InputVertexData<double>& values, const PreviewOptions& options = {});

// Competing species (common/model/species.hpp): one fixed colour per species (species_colour), added on a
// dark base in proportion to each layer's normalised value (colorings[s]: its levels, e.g. 0 .. 2 U_s
// of that species), so every species' network shows in its own colour and overlaps mix. InputError
// unless there are as many colourings as layers (at least one) and each layer has a value per vertex.
RgbImage render_species_preview(const InputMesh& mesh, const std::vector<InputVertexData<double>>& layers,
                                const std::vector<FieldColoring>& colorings, const PreviewOptions& options = {});
// Species s's colour, components in [0, 1] (a fixed palette of 8, repeated beyond).
std::array<double, 3> species_colour(int species);

// Layers in their own colour sets (common/color/layer_colours.hpp): at each point the first layer's
// field, the final field and the first layer's share, interpolated in the triangle, coloured by
// `colours`. InputError on a size mismatch.
RgbImage render_layers_preview(const InputMesh& mesh, const InputVertexData<double>& first, const InputVertexData<double>& last,
                               const InputVertexData<double>& first_share, const LayerColours& colours,
                               const PreviewOptions& options = {});

// Writes an 8-bit RGB PNG at `path` (temporary file and rename); InputError naming `path` when it
// cannot be written.
void write_rgb_png(const std::string& path, const RgbImage& image);

// Renders and writes a PNG at `path`; InputError naming `path` when it cannot be written (then no
// file, not even a partial one, is left there).
void write_preview_png(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                       const PreviewOptions& options = {});

}  // namespace physarum
