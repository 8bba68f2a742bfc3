#include "common/colormap.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

// Nine evenly spaced samples (t = 0, 1/8, ..., 1) of matplotlib's viridis and magma maps, as their
// widely published hex values; piecewise-linear interpolation between them stays within a few
// levels of the full 256-entry tables, well below what a preview picture shows.
constexpr std::array<std::array<std::uint8_t, 3>, 9> kViridis = {{
    {0x44, 0x01, 0x54}, {0x47, 0x2D, 0x7B}, {0x3B, 0x52, 0x8B}, {0x2C, 0x72, 0x8E}, {0x21, 0x90, 0x8C},
    {0x27, 0xAD, 0x81}, {0x5D, 0xC8, 0x63}, {0xAA, 0xDC, 0x32}, {0xFD, 0xE7, 0x25},
}};
constexpr std::array<std::array<std::uint8_t, 3>, 9> kMagma = {{
    {0x00, 0x00, 0x04}, {0x1D, 0x11, 0x47}, {0x51, 0x12, 0x7C}, {0x83, 0x26, 0x81}, {0xB7, 0x37, 0x79},
    {0xE7, 0x52, 0x63}, {0xFC, 0x89, 0x61}, {0xFE, 0xC2, 0x87}, {0xFC, 0xFD, 0xBF},
}};

}  // namespace

std::array<double, 3> colormap_color_float(Colormap map, double t) {
  const auto& table = map == Colormap::Magma ? kMagma : kViridis;
  if (!(t > 0.0)) t = 0.0;  // also catches NaN
  t = std::min(t, 1.0);
  const double x = t * static_cast<double>(table.size() - 1);
  const size_t i = std::min(static_cast<size_t>(x), table.size() - 2);
  const double f = x - static_cast<double>(i);
  std::array<double, 3> rgb{};
  for (int c = 0; c < 3; ++c) rgb[c] = ((1.0 - f) * table[i][c] + f * table[i + 1][c]) / 255.0;
  return rgb;
}

Rgb8 colormap_color(Colormap map, double t) {
  const auto rgb = colormap_color_float(map, t);
  Rgb8 out{};
  for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(rgb[c], 0.0, 1.0) * 255.0));
  return out;
}

}  // namespace physarum
