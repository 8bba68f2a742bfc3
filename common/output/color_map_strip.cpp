#include "common/output/color_map_strip.hpp"

#include "common/base/errors.hpp"

namespace physarum {

RgbImage color_map_strip(const ColorMap& map, int width, int height) {
  if (width < 2 || width > 16384 || height < 1 || height > 16384)
    throw InputError("colour-map strip: size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is outside 2..16384 x 1..16384");
  RgbImage image;
  image.width = width;
  image.height = height;
  image.pixels.resize(static_cast<size_t>(width) * height * 3);
  for (int x = 0; x < width; ++x) {
    const Rgb8 c = map.sample8(static_cast<double>(x) / (width - 1));
    for (int y = 0; y < height; ++y)
      for (int ch = 0; ch < 3; ++ch) image.pixels[(static_cast<size_t>(y) * width + x) * 3 + ch] = c[ch];
  }
  return image;
}

void write_color_map_strip_png(const std::string& path, const ColorMap& map, int width, int height) {
  write_rgb_png(path, color_map_strip(map, width, height));
}

}  // namespace physarum
