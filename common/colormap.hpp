#pragma once
// Perceptually uniform colour maps for pictures of scalar fields (PLY vertex colours, preview
// image): lightness rises monotonically, so brighter always means more pheromone.
#include <array>
#include <cstdint>

namespace physarum {

enum class Colormap { Viridis, Magma };

using Rgb8 = std::array<std::uint8_t, 3>;

// t in [0, 1] (clamped; NaN maps to 0) to an sRGB colour.
Rgb8 colormap_color(Colormap map, double t);
// Floating-point sRGB in [0, 1], for shading before quantising.
std::array<double, 3> colormap_color_float(Colormap map, double t);

}  // namespace physarum
