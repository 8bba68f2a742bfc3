#pragma once
// A baked texture as image files, written through OpenImageIO to a temporary name and renamed (no
// half-written file is ever left at the final name):
//   colour PNG, 8 or 16 bits per channel: one field through a colour map (FieldColoring, the same
//     value -> colour rule as the PLY vertex colours and the preview), sRGB, RGB; texels outside
//     every chart beyond the padding take a background colour;
//   float EXR: the raw values, one 32-bit float channel per field named after it (e.g. "pheromone"),
//     for tools that colour or threshold the field themselves; background texels hold the bake's
//     background value.
// Both have the texture's rows top first (v = 0 at the bottom, as glTF and OBJ read UVs).
#include "common/output/ply_writer.hpp"
#include "common/output/texture_bake.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace physarum {

struct TextureColouring {
  FieldColoring coloring;  // value -> colour
  // The value at the top of the colour map (FieldColoring::upper of the field's vertex values, so the
  // texture's colours are those of the PLY files).
  double upper_end = 1.0;
  Rgb8 background = {0, 0, 0};  // texels outside every chart and its padding
};

// The 8-bit sRGB RGB pixels of channel `channel` (row-major, top row first: exactly what
// write_texture_png writes at 8 bits), for embedding elsewhere (a glTF baseColorTexture). InputError
// when the channel does not exist.
std::vector<std::uint8_t> texture_rgb8(const BakedTexture& texture, std::size_t channel, const TextureColouring& colouring);

// The 8-bit sRGB pixels of a texture coloured from all its channels at once: `colour` gets each
// chart or padding texel's channel values (in the texture's channel order), as for a colour composed
// of several fields (common/color/layer_colours.hpp); background texels are `background`.
std::vector<std::uint8_t> composed_texture_rgb8(const BakedTexture& texture,
                                                const std::function<SrgbColor(const float* channels)>& colour,
                                                const Rgb8& background = {0, 0, 0});

// Writes channel `channel` of `texture` as an RGB PNG with `bits` (8 or 16) per channel at `path`.
// InputError naming `path` when the channel does not exist, bits is neither 8 nor 16, or the file
// cannot be written.
void write_texture_png(const std::string& path, const BakedTexture& texture, std::size_t channel,
                       const TextureColouring& colouring, int bits = 8);

// Writes every channel of `texture` as 32-bit floats to an OpenEXR file at `path` (channels named
// as the texture's). InputError naming `path` when it cannot be written.
void write_texture_exr(const std::string& path, const BakedTexture& texture);

}  // namespace physarum
