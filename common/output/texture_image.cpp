#include "common/output/texture_image.hpp"

#include "common/base/atomic_write.hpp"
#include "common/color/color_map.hpp"
#include "common/base/errors.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace physarum {
namespace {

// Writes `pixels` (rows top first, `spec`'s layout) in OpenImageIO's format `format` through a
// temporary file (whose name does not end in the format's extension, hence the explicit format).
void write_image_atomically(const std::string& path, const char* format, const OIIO::ImageSpec& spec,
                            OIIO::TypeDesc pixel_type, const void* pixels) {
  write_file_atomically(path, [&](const std::string& temporary) {
    auto out = OIIO::ImageOutput::create(format);
    if (!out) throw InputError(path + ": cannot write " + format + ": " + OIIO::geterror());
    if (!out->open(temporary, spec)) throw InputError(path + ": cannot write " + format + ": " + out->geterror());
    const bool written = out->write_image(pixel_type, pixels);
    const std::string error = written ? std::string() : out->geterror();
    if (!out->close() || !written)
      throw InputError(path + ": cannot write " + format + ": " + (error.empty() ? out->geterror() : error));
  });
}

// RGB words of full scale Word's maximum (255 or 65535), rows top first: `colour(texel's channel
// values)` for each chart or padding texel, the background colour elsewhere (8-bit colours scale to
// 16 bits by 257, so 255 stays full scale).
template <typename Word, typename Colour>
std::vector<Word> coloured_pixels(const BakedTexture& texture, const Colour& colour, const Rgb8& background) {
  constexpr double kFullScale = std::numeric_limits<Word>::max();
  const size_t texels = static_cast<size_t>(texture.width) * static_cast<size_t>(texture.height);
  std::vector<Word> pixels(texels * 3);
  for (size_t t = 0; t < texels; ++t) {
    if (texture.coverage[t] == TexelCoverage::Background) {
      for (int c = 0; c < 3; ++c) pixels[3 * t + c] = static_cast<Word>(std::lround(background[c] / 255.0 * kFullScale));
      continue;
    }
    const SrgbColor rgb = colour(&texture.values[t * texture.channels.size()]);
    for (int c = 0; c < 3; ++c) pixels[3 * t + c] = static_cast<Word>(std::lround(std::clamp(rgb[c], 0.0, 1.0) * kFullScale));
  }
  return pixels;
}

// One channel through the colour map.
template <typename Word>
std::vector<Word> coloured_pixels(const BakedTexture& texture, std::size_t channel, const TextureColouring& colouring) {
  return coloured_pixels<Word>(
      texture,
      [&](const float* values) {
        return color_map_color_float(colouring.coloring.map, colouring.coloring.normalise(values[channel], colouring.upper_end));
      },
      colouring.background);
}

}  // namespace

std::vector<std::uint8_t> texture_rgb8(const BakedTexture& texture, std::size_t channel, const TextureColouring& colouring) {
  if (channel >= texture.channels.size())
    throw InputError("texture: it has " + std::to_string(texture.channels.size()) + " channels, no channel " +
                     std::to_string(channel));
  return coloured_pixels<std::uint8_t>(texture, channel, colouring);
}

std::vector<std::uint8_t> composed_texture_rgb8(const BakedTexture& texture,
                                                const std::function<SrgbColor(const float* channels)>& colour,
                                                const Rgb8& background) {
  return coloured_pixels<std::uint8_t>(texture, colour, background);
}

void write_texture_png(const std::string& path, const BakedTexture& texture, std::size_t channel,
                       const TextureColouring& colouring, int bits) {
  if (channel >= texture.channels.size())
    throw InputError(path + ": the texture has " + std::to_string(texture.channels.size()) + " channels, no channel " +
                     std::to_string(channel));
  if (bits != 8 && bits != 16) throw InputError(path + ": PNG texture depth " + std::to_string(bits) + " is neither 8 nor 16");
  OIIO::ImageSpec spec(texture.width, texture.height, 3, bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
  spec.attribute("oiio:ColorSpace", "sRGB");
  if (bits == 8) {
    const std::vector<std::uint8_t> pixels = coloured_pixels<std::uint8_t>(texture, channel, colouring);
    write_image_atomically(path, "png", spec, OIIO::TypeDesc::UINT8, pixels.data());
  } else {
    const std::vector<std::uint16_t> pixels = coloured_pixels<std::uint16_t>(texture, channel, colouring);
    write_image_atomically(path, "png", spec, OIIO::TypeDesc::UINT16, pixels.data());
  }
}

void write_texture_exr(const std::string& path, const BakedTexture& texture) {
  if (texture.channels.empty()) throw InputError(path + ": a texture without channels");
  OIIO::ImageSpec spec(texture.width, texture.height, static_cast<int>(texture.channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = texture.channels;
  spec.attribute("compression", "zip");
  write_image_atomically(path, "openexr", spec, OIIO::TypeDesc::FLOAT, texture.values.data());
}

}  // namespace physarum
