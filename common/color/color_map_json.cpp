#include "common/color/color_map_json.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace physarum {
namespace {

using nlohmann::json;

constexpr const char* kKeys[] = {"name", "stops", "gamma", "remap", "levels"};

double number_at(const json& v, const std::string& where) {
  if (!v.is_number()) throw InputError(where + " = " + v.dump() + " is not a number");
  return v.get<double>();
}

ColorStop parse_stop(const json& s, const std::string& where) {
  if (!s.is_array() || (s.size() != 2 && s.size() != 4))
    throw InputError(where + " = " + s.dump() + " is not [position, \"#rrggbb\"] or [position, r, g, b]");
  ColorStop stop;
  stop.position = number_at(s[0], where + " position");
  if (s.size() == 2) {
    if (!s[1].is_string()) throw InputError(where + " colour = " + s[1].dump() + " is not a \"#rrggbb\" string");
    stop.color = parse_hex_color(s[1].get<std::string>(), where);
  } else {
    for (int c = 0; c < 3; ++c) stop.color[c] = number_at(s[1 + c], where + " component " + std::to_string(c));
  }
  return stop;
}

std::string read_text(const std::string& path, const char* what) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the " + std::string(what));
  std::stringstream buffer;
  buffer << file.rdbuf();
  if (file.bad()) throw InputError(path + ": cannot read the " + std::string(what));
  return buffer.str();
}

bool is_built_in(const std::string& name) {
  const auto& names = ColorMap::names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// "#rrggbb,#rrggbb,...": two or more colours, equally spaced from the map's start to its end.
ColorMapSettings color_list_settings(const std::string& text, const std::string& where) {
  std::vector<ColorStop> stops;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) {
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    stops.push_back({0.0, parse_hex_color(item, where)});
  }
  if (stops.size() < 2) throw InputError(where + " = \"" + text + "\": a colour list needs two or more colours, separated by commas");
  for (size_t k = 0; k < stops.size(); ++k) stops[k].position = static_cast<double>(k) / static_cast<double>(stops.size() - 1);
  ColorMapSettings settings;
  settings.map = ColorMap(text, std::move(stops));
  return settings;
}

}  // namespace

std::string hex_color(const Rgb8& color) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", color[0], color[1], color[2]);
  return text;
}

SrgbColor parse_hex_color(const std::string& text, const std::string& where) {
  const bool well_formed = text.size() == 7 && text[0] == '#' &&
                           std::all_of(text.begin() + 1, text.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
  if (!well_formed) throw InputError(where + ": colour \"" + text + "\" is not of the form \"#rrggbb\"");
  SrgbColor color{};
  for (int c = 0; c < 3; ++c) color[c] = std::stoi(text.substr(1 + 2 * c, 2), nullptr, 16) / 255.0;
  return color;
}

ColorMapping ColorMapSettings::mapping(double unit) const {
  ColorMapping m;
  m.map = map;
  m.low = levels[0] * unit;
  m.high = levels[1] * unit;
  m.gamma = gamma;
  m.remap = remap;
  return m;
}

ColorMapSettings color_map_settings_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) throw InputError(where + ": a colour map must be a JSON object, found " + std::string(j.type_name()));
  for (auto it = j.begin(); it != j.end(); ++it)
    if (std::find(std::begin(kKeys), std::end(kKeys), it.key()) == std::end(kKeys))
      throw InputError(where + ": unknown key '" + it.key() + "' (a colour map has name, stops, gamma, remap, levels)");

  std::string name;
  if (auto it = j.find("name"); it != j.end()) {
    if (!it->is_string()) throw InputError(where + ": 'name' = " + it->dump() + " is not a string");
    name = it->get<std::string>();
  }
  ColorMapSettings settings;
  if (auto it = j.find("stops"); it != j.end()) {
    if (!it->is_array()) throw InputError(where + ": 'stops' = " + it->dump() + " is not a list of stops");
    std::vector<ColorStop> stops;
    for (size_t i = 0; i < it->size(); ++i)
      stops.push_back(parse_stop((*it)[i], where + ": 'stops' entry " + std::to_string(i)));
    if (const std::string problem = ColorMap::stops_problem(stops); !problem.empty())
      throw InputError(where + ": 'stops' " + problem);
    settings.map = ColorMap(name.empty() ? "custom" : name, std::move(stops));
  } else if (!name.empty()) {
    try {
      settings.map = ColorMap::named(name);
    } catch (const InputError& e) {
      throw InputError(where + ": 'name' without 'stops': " + e.what());
    }
  } else {
    throw InputError(where + ": needs 'stops' (or 'name', a built-in map)");
  }

  if (auto it = j.find("gamma"); it != j.end()) {
    settings.gamma = number_at(*it, where + ": 'gamma'");
    if (!(settings.gamma > 0.0) || !std::isfinite(settings.gamma))
      throw InputError(where + ": 'gamma' = " + it->dump() + " must be a finite number > 0");
  }
  if (auto it = j.find("remap"); it != j.end()) {
    if (!it->is_array()) throw InputError(where + ": 'remap' = " + it->dump() + " is not a list of [x, y] points");
    std::vector<std::pair<double, double>> points;
    for (size_t i = 0; i < it->size(); ++i) {
      const json& p = (*it)[i];
      const std::string at = where + ": 'remap' point " + std::to_string(i);
      if (!p.is_array() || p.size() != 2) throw InputError(at + " = " + p.dump() + " is not [x, y]");
      points.emplace_back(number_at(p[0], at + " x"), number_at(p[1], at + " y"));
    }
    settings.remap = RemapCurve(std::move(points), where + ": 'remap'");
  }
  if (auto it = j.find("levels"); it != j.end()) {
    if (!it->is_array() || it->size() != 2) throw InputError(where + ": 'levels' = " + it->dump() + " is not [low, high]");
    const double low = number_at((*it)[0], where + ": 'levels' low");
    const double high = number_at((*it)[1], where + ": 'levels' high");
    if (!std::isfinite(low) || !std::isfinite(high) || !(high > low))
      throw InputError(where + ": 'levels' = " + it->dump() + " must be finite with low < high (multiples of U)");
    settings.levels = {low, high};
  }
  return settings;
}

ColorMapSettings read_color_map_file(const std::string& path) {
  const std::string text = read_text(path, "colour-map file");
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string message = e.what();
    if (auto pos = message.find("] "); pos != std::string::npos) message = message.substr(pos + 2);
    throw InputError(path + ": malformed JSON: " + message);
  }
  return color_map_settings_from_json(j, path);
}

ColorMapSettings resolve_color_map(const json& value, const std::string& scene_folder, const std::string& where) {
  if (value.is_object()) return color_map_settings_from_json(value, where);
  if (!value.is_string())
    throw InputError(where + " = " + value.dump() + " has the wrong type (" + value.type_name() +
                     "; expected a map name, a path to a colour-map file or an object)");
  const std::string text = value.get<std::string>();
  if (text.rfind('#', 0) == 0) return color_list_settings(text, where);
  if (is_built_in(text)) {
    ColorMapSettings settings;
    settings.map = ColorMap::named(text);
    return settings;
  }
  std::filesystem::path path(text);
  const bool looks_like_path = path.has_parent_path() || path.extension() == ".json";
  if (!looks_like_path) {
    std::string list;
    for (const std::string& n : ColorMap::names()) list += (list.empty() ? "" : ", ") + n;
    throw InputError(where + " = \"" + text + "\" is neither a built-in colour map (" + list +
                     ") nor a path to a .json colour-map file");
  }
  if (path.is_relative()) path = std::filesystem::path(scene_folder) / path;
  path = path.lexically_normal();
  if (!std::filesystem::exists(path))
    throw InputError(where + " = \"" + text + "\": file not found (looked for " + path.string() + ")");
  return read_color_map_file(path.string());
}

nlohmann::ordered_json color_map_settings_json(const ColorMapSettings& s) {
  nlohmann::ordered_json j;
  j["name"] = s.map.name();
  nlohmann::ordered_json stops = nlohmann::ordered_json::array();
  for (const ColorStop& stop : s.map.stops())
    stops.push_back({std::round(stop.position * 1e6) / 1e6, hex_color(to_rgb8(stop.color))});
  j["stops"] = std::move(stops);
  j["gamma"] = s.gamma;
  if (!s.remap.identity()) {
    nlohmann::ordered_json remap = nlohmann::ordered_json::array();
    for (const auto& [x, y] : s.remap.points()) remap.push_back({x, y});
    j["remap"] = std::move(remap);
  }
  j["levels"] = {s.levels[0], s.levels[1]};
  return j;
}

void write_color_map_file(const std::string& path, const ColorMapSettings& settings) {
  // One line per key and one per stop: a 256-stop map stays readable and diffs line by line.
  const nlohmann::ordered_json j = color_map_settings_json(settings);
  std::string text = "{\n";
  for (auto it = j.begin(); it != j.end(); ++it) {
    // Appended piece by piece: operator+ chains trip a GCC 12 -Wrestrict false positive.
    text.append(" ").append(nlohmann::ordered_json(it.key()).dump()).append(": ");
    if (it.key() == "stops") {
      text += "[\n";
      for (size_t i = 0; i < it->size(); ++i) text.append("  ").append((*it)[i].dump()).append(i + 1 < it->size() ? ",\n" : "\n");
      text += " ]";
    } else {
      text += it->dump();
    }
    text += std::next(it) != j.end() ? ",\n" : "\n";
  }
  write_text_file_atomically(path, text + "}\n");
}

}  // namespace physarum
