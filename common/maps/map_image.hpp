#pragma once
// An image read as a map source ({"texture": FILE, "channel": ...}): its pixels as floats through
// OpenImageIO (8-bit 255 -> 1.0, 16-bit 65535 -> 1.0, float files as stored; no colour-space
// conversion, so a painted grey of 128 reads 0.502), sampled bilinearly at a UV.
//
// UV conventions are those of the baked textures (common/output/texture_bake.hpp): v = 0 at the BOTTOM
// of the image, texel (column i, row r from the top) has its centre at u = (i + 0.5) / W,
// v = 1 - (r + 0.5) / H, and UVs outside [0, 1] WRAP (repeat, glTF's default sampler) — so does the
// bilinear footprint at the image's edges, as a tiling texture expects.
#include "common/maps/map_definition.hpp"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace physarum {

struct MapImage {
  std::string path;
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // row-major, top row first, `channels` floats per pixel

  // The channel's value at pixel (i, j) (j from the top): red, green and blue of a grey image are its
  // grey; alpha is the last channel of a grey+alpha or RGBA image; luma is Rec. 709's
  // 0.2126 R + 0.7152 G + 0.0722 B (the grey itself for a grey image).
  double texel(TextureChannel channel, int i, int j) const;
  // Bilinear interpolation of the four texels around `uv`, wrapped.
  double sample(TextureChannel channel, const Eigen::Vector2d& uv) const;
};

// InputError naming `path` (and `what`, the scene key and map) when the file cannot be read as an
// image, or when `channel` is alpha and the image has none.
MapImage read_map_image(const std::string& path, TextureChannel channel, const std::string& what);

}  // namespace physarum
