#pragma once
// A colour map drawn as a horizontal strip, t = 0 at the left edge and t = 1 at the right: how a map
// file is previewed (`physarum color_map --strip`) before it is used on a surface.
#include "common/color/color_map.hpp"
#include "common/output/preview_image.hpp"

#include <string>

namespace physarum {

// Column x shows map.sample8(x / (width - 1)) over the full height. InputError when a size is
// outside 2..16384 (width) or 1..16384 (height).
RgbImage color_map_strip(const ColorMap& map, int width = 512, int height = 64);

// Draws the strip and writes it as an 8-bit RGB PNG (temporary file and rename).
void write_color_map_strip_png(const std::string& path, const ColorMap& map, int width = 512, int height = 64);

}  // namespace physarum
