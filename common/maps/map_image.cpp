#include "common/maps/map_image.hpp"

#include "common/base/image_budget.hpp"

#include "common/base/errors.hpp"

#include <OpenImageIO/imageio.h>

#include <cmath>

namespace physarum {
namespace {

int wrap(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

}  // namespace

double MapImage::texel(TextureChannel channel, int i, int j) const {
  const float* p = pixels.data() + (static_cast<size_t>(j) * static_cast<size_t>(width) + static_cast<size_t>(i)) *
                                       static_cast<size_t>(channels);
  const bool colour = channels >= 3;
  switch (channel) {
    case TextureChannel::Red: return p[0];
    case TextureChannel::Green: return colour ? p[1] : p[0];
    case TextureChannel::Blue: return colour ? p[2] : p[0];
    case TextureChannel::Alpha: return p[channels - 1];
    case TextureChannel::Luma: return colour ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : p[0];
  }
  return 0.0;
}

double MapImage::sample(TextureChannel channel, const Eigen::Vector2d& uv) const {
  // Continuous texel coordinates whose integer points are texel centres (row 0 at the top).
  const double x = uv.x() * width - 0.5, y = (1.0 - uv.y()) * height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  // Wrapping first keeps the integer arithmetic small for UVs many tiles away.
  const int i0 = wrap(static_cast<int>(std::fmod(fx, static_cast<double>(width))), width), i1 = wrap(i0 + 1, width);
  const int j0 = wrap(static_cast<int>(std::fmod(fy, static_cast<double>(height))), height), j1 = wrap(j0 + 1, height);
  return (1.0 - ty) * ((1.0 - tx) * texel(channel, i0, j0) + tx * texel(channel, i1, j0)) +
         ty * ((1.0 - tx) * texel(channel, i0, j1) + tx * texel(channel, i1, j1));
}

MapImage read_map_image(const std::string& path, TextureChannel channel, const std::string& what) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(what + ": cannot read the image " + path + " (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  MapImage image;
  image.path = path;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  if (image.width < 1 || image.height < 1 || image.channels < 1)
    throw InputError(what + ": the image " + path + " is empty");
  check_image_budget(image.width, image.height, path, what);
  if (channel == TextureChannel::Alpha && image.channels != 2 && image.channels != 4)
    throw InputError(what + ": channel \"a\": the image " + path + " has " + std::to_string(image.channels) +
                     " channel(s) and no alpha");
  image.pixels.resize(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
                      static_cast<size_t>(image.channels));
  if (!in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    throw InputError(what + ": cannot read the image " + path + " (" + in->geterror() + ")");
  in->close();
  return image;
}

}  // namespace physarum
