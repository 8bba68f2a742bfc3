#pragma once
// A colour map: sRGB colours ("stops") at positions in [0, 1], interpolated piecewise linearly, that
// turns a normalised value t into a colour for pictures of scalar fields (PLY vertex colours, the
// preview image, textures). Named maps are built in (`ColorMap::named`): matplotlib's perceptual
// viridis, magma and inferno, a linear grey ramp, and a few natural palettes; other maps come from
// colour-map files (common/color/color_map_json.hpp) or exemplar images (common/color/isomap_color_map.hpp).
//
// Interpolation happens in sRGB (the gamma-encoded values), not in linear light: that is how
// matplotlib defines its maps from their tables, so viridis and magma stay exactly the published
// colours between the samples as before, and the image-assisted maps are sampled densely enough
// (256 stops) that the space of the in-between blend does not show.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace physarum {

using Rgb8 = std::array<std::uint8_t, 3>;
using SrgbColor = std::array<double, 3>;  // sRGB components in [0, 1]

struct ColorStop {
  double position = 0.0;  // in [0, 1]
  SrgbColor color{};
};

class ColorMap {
 public:
  // Throws InputError naming the map when `stops` is not a valid list (see stops_problem).
  ColorMap(std::string name, std::vector<ColorStop> stops);

  // A built-in map by name (names()); InputError listing the names for any other.
  static ColorMap named(std::string_view name);
  static ColorMap viridis();
  // The built-in names, in the order the help texts list them.
  static const std::vector<std::string>& names();

  // "" when `stops` is a valid list, else what is wrong, for messages: at least two stops, positions
  // finite, inside [0, 1] and non-decreasing (two stops at one position make a sharp edge), every
  // component finite and inside [0, 1].
  static std::string stops_problem(const std::vector<ColorStop>& stops);

  const std::string& name() const { return name_; }
  const std::vector<ColorStop>& stops() const { return stops_; }

  // The colour at t (clamped to [0, 1]; NaN maps to 0); before the first stop the first colour,
  // after the last the last one.
  SrgbColor sample(double t) const;
  // The same, rounded to 8 bits.
  Rgb8 sample8(double t) const;

 private:
  std::string name_;
  std::vector<ColorStop> stops_;
};

// Rounds a float sRGB colour (components clamped to [0, 1]) to 8 bits.
Rgb8 to_rgb8(const SrgbColor& color);

// t in [0, 1] (clamped; NaN maps to 0) to an sRGB colour: map.sample8(t) and map.sample(t).
Rgb8 color_map_color(const ColorMap& map, double t);
std::array<double, 3> color_map_color_float(const ColorMap& map, double t);

}  // namespace physarum
