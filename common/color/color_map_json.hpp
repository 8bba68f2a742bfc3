#pragma once
// Colour maps as JSON: a colour-map file (MAP.json) and a scene's "colormap" value.
//
// A colour-map file is one object:
//   {"name": "lichen",                        optional label; alone (no "stops") it names a built-in map
//    "stops": [[0, "#8e8b82"], [0.4, "#a9b489"], ...]   or [[pos, r, g, b], ...] with r, g, b in [0, 1]
//    "gamma": 1.0,                            optional, > 0 (t -> t^gamma)
//    "remap": [[0, 0], [0.5, 1], [1, 0]],     optional piecewise-linear curve, x strictly increasing
//    "levels": [0, 2]}                        optional input range, in multiples of the uniform steady
//                                             state U (the colours of `physarum run` span 0 .. 2U)
// Stops are sRGB, sorted by position in [0, 1]; at least two (common/color/color_map.hpp). The levels are
// in units of U so that one map file suits scenes of any size and agent count.
//
// A scene's "colormap" is a built-in name ("viridis"), a path to such a file (relative to the scene
// file's folder, or absolute), a list of two or more colours "#rrggbb,#rrggbb,..." (equally spaced
// stops, first to last), or an object of the same form inline. Every error is an InputError
// naming the file or key and what is wrong.
#include "common/color/color_mapping.hpp"

#include <array>
#include <string>

#include <nlohmann/json.hpp>

namespace physarum {

// What a colour-map file says: the map and its reparameterisation, levels still relative to U.
struct ColorMapSettings {
  ColorMap map = ColorMap::viridis();
  std::array<double, 2> levels{0.0, 2.0};  // low, high in multiples of U
  double gamma = 1.0;
  RemapCurve remap;

  // The mapping for a field whose uniform steady state is `unit`: levels scaled by it.
  ColorMapping mapping(double unit) const;
};

// Parses the object form; `where` ("MAP.json", "scene.json: key 'colormap'") prefixes every message.
ColorMapSettings color_map_settings_from_json(const nlohmann::json& object, const std::string& where);

// Reads and parses a colour-map file.
ColorMapSettings read_color_map_file(const std::string& path);

// A scene's "colormap" value (name, path or object); relative paths are resolved against
// `scene_folder`; `where` names the scene file and key for messages.
ColorMapSettings resolve_color_map(const nlohmann::json& value, const std::string& scene_folder, const std::string& where);

// The object form; stops as [position, "#rrggbb"] (8-bit), everything else as given. Reading it back
// gives the same map up to 8-bit rounding of the colours.
nlohmann::ordered_json color_map_settings_json(const ColorMapSettings& settings);

// Writes color_map_settings_json to `path` through a temporary file and rename.
void write_color_map_file(const std::string& path, const ColorMapSettings& settings);

// "#rrggbb" (lower case) for an 8-bit colour, and back: InputError naming `where` for anything but
// '#' and six hex digits.
std::string hex_color(const Rgb8& color);
SrgbColor parse_hex_color(const std::string& text, const std::string& where);

}  // namespace physarum
