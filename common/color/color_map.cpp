#include "common/color/color_map.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

namespace physarum {
namespace {

// Evenly spaced stops from 8-bit hex colours 0xRRGGBB.
std::vector<ColorStop> even_stops(std::initializer_list<std::uint32_t> hex) {
  std::vector<ColorStop> stops;
  const double last = static_cast<double>(hex.size() - 1);
  size_t i = 0;
  for (std::uint32_t h : hex) {
    stops.push_back({static_cast<double>(i++) / last,
                     {((h >> 16) & 0xFF) / 255.0, ((h >> 8) & 0xFF) / 255.0, (h & 0xFF) / 255.0}});
  }
  return stops;
}

// Stops at given positions.
std::vector<ColorStop> placed_stops(std::initializer_list<std::pair<double, std::uint32_t>> stops_in) {
  std::vector<ColorStop> stops;
  for (const auto& [position, h] : stops_in)
    stops.push_back({position, {((h >> 16) & 0xFF) / 255.0, ((h >> 8) & 0xFF) / 255.0, (h & 0xFF) / 255.0}});
  return stops;
}

struct NamedMap {
  const char* name;
  std::function<std::vector<ColorStop>()> stops;
};

const std::vector<NamedMap>& named_maps() {
  static const std::vector<NamedMap> maps = {
      // matplotlib's perceptual maps: nine samples of their 256-entry tables (entries 0, 32, 64, 96,
      // 128, 160, 192, 223, 255, the widely published 9-class values); piecewise-linear
      // interpolation between them stays within a few levels of the full tables, well below what a
      // picture shows. Lightness rises monotonically, so brighter always means more pheromone.
      {"viridis", [] { return even_stops({0x440154, 0x472D7B, 0x3B528B, 0x2C728E, 0x21908C, 0x27AD81, 0x5DC863,
                                          0xAADC32, 0xFDE725}); }},
      {"magma", [] { return even_stops({0x000004, 0x1D1147, 0x51127C, 0x832681, 0xB73779, 0xE75263, 0xFC8961,
                                        0xFEC287, 0xFCFDBF}); }},
      {"inferno", [] { return even_stops({0x000004, 0x210C4A, 0x57106E, 0x8A226A, 0xBC3754, 0xE45A31, 0xF98E09,
                                          0xF9C932, 0xFCFFA4}); }},
      // Linear in the stored sRGB value: for masks and height-like uses where the number itself
      // should become the grey level (as an 8-bit greyscale image would store it).
      {"grey", [] { return even_stops({0x000000, 0xFFFFFF}); }},
      // ---- natural palettes (designed here; not perceptually uniform, meant to look like things) ----
      // Physarum polycephalum itself: the plasmodium's chrome-yellow veins on pale, damp substrate;
      // the densest tubes turn a deeper orange-yellow.
      {"physarum", [] { return placed_stops({{0.0, 0xEEE8D5}, {0.35, 0xF1DD8A}, {0.7, 0xF4C21B}, {1.0, 0xD68A00}}); }},
      // Moss on peat: dark brown-black ground, a cushion of deep green, sunlit yellow-green tips
      // where the field is strongest (lightness rises, so it also reads as a sequential map).
      {"moss", [] { return placed_stops({{0.0, 0x1B1A12}, {0.3, 0x2F4A1C}, {0.65, 0x6B8E23}, {1.0, 0xC9D86B}}); }},
      // Looking down into the sea: abyssal navy, deep teal, turquoise shallows, white foam on the
      // peaks; suits networks seen as currents or bioluminescence.
      {"ocean", [] { return placed_stops({{0.0, 0x03101F}, {0.35, 0x0B4F6C}, {0.7, 0x2A9D8F}, {1.0, 0xD8F3EC}}); }},
      // Glowing embers: ash-black, deep crimson, flame orange, a near-white core; warmer and redder
      // than inferno, for networks that should look hot.
      {"ember", [] { return placed_stops({{0.0, 0x0B0706}, {0.3, 0x5A0F0A}, {0.6, 0xC1340F}, {0.85, 0xF79A1E},
                                          {1.0, 0xFFF1C1}}); }},
      // Lichen on bark: the grey of the bark as background, a sage-green crust, then the ochre and
      // rust orange of Xanthoria where the growth is densest (lightness falls at the top end: the
      // background is the light colour, as on a real trunk).
      {"lichen", [] { return placed_stops({{0.0, 0x8E8B82}, {0.4, 0xA9B489}, {0.75, 0xD9A521}, {1.0, 0xC8580F}}); }},
  };
  return maps;
}

}  // namespace

std::string ColorMap::stops_problem(const std::vector<ColorStop>& stops) {
  if (stops.size() < 2)
    return "needs at least 2 stops, has " + std::to_string(stops.size());
  for (size_t i = 0; i < stops.size(); ++i) {
    const ColorStop& s = stops[i];
    const std::string which = "stop " + std::to_string(i);
    if (!std::isfinite(s.position) || s.position < 0.0 || s.position > 1.0)
      return which + ": position " + std::to_string(s.position) + " is outside [0, 1]";
    if (i > 0 && s.position < stops[i - 1].position)
      return which + ": position " + std::to_string(s.position) + " is below the previous stop's " +
             std::to_string(stops[i - 1].position) + " (stops must be sorted by position)";
    for (double c : s.color)
      if (!std::isfinite(c) || c < 0.0 || c > 1.0)
        return which + ": colour component " + std::to_string(c) + " is outside [0, 1]";
  }
  return {};
}

ColorMap::ColorMap(std::string name, std::vector<ColorStop> stops) : name_(std::move(name)), stops_(std::move(stops)) {
  if (const std::string problem = stops_problem(stops_); !problem.empty())
    throw InputError("colour map '" + name_ + "': " + problem);
}

const std::vector<std::string>& ColorMap::names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const NamedMap& m : named_maps()) n.emplace_back(m.name);
    return n;
  }();
  return names;
}

ColorMap ColorMap::named(std::string_view name) {
  for (const NamedMap& m : named_maps())
    if (name == m.name) return ColorMap(m.name, m.stops());
  std::string list;
  for (const std::string& n : names()) list += (list.empty() ? "" : ", ") + n;
  throw InputError("unknown colour map '" + std::string(name) + "' (the built-in maps are " + list + ")");
}

ColorMap ColorMap::viridis() { return named("viridis"); }

SrgbColor ColorMap::sample(double t) const {
  if (!(t > 0.0)) t = 0.0;  // also catches NaN
  t = std::min(t, 1.0);
  // The first stop whose position exceeds t; the colour lies between it and the one before.
  const auto upper = std::upper_bound(stops_.begin(), stops_.end(), t,
                                      [](double value, const ColorStop& s) { return value < s.position; });
  if (upper == stops_.begin()) return stops_.front().color;
  if (upper == stops_.end()) return stops_.back().color;
  const ColorStop& a = *(upper - 1);
  const ColorStop& b = *upper;
  const double f = (t - a.position) / (b.position - a.position);  // b.position > t >= a.position
  SrgbColor rgb{};
  for (int c = 0; c < 3; ++c) rgb[c] = (1.0 - f) * a.color[c] + f * b.color[c];
  return rgb;
}

Rgb8 to_rgb8(const SrgbColor& color) {
  Rgb8 out{};
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(color[c], 0.0, 1.0) * 255.0));
  return out;
}

Rgb8 ColorMap::sample8(double t) const { return to_rgb8(sample(t)); }

Rgb8 color_map_color(const ColorMap& map, double t) { return map.sample8(t); }
std::array<double, 3> color_map_color_float(const ColorMap& map, double t) { return map.sample(t); }

}  // namespace physarum
