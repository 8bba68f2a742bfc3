#include "common/maps/map_definition.hpp"

#include "common/base/errors.hpp"
#include "common/maps/inline_maps.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <string_view>

namespace physarum {
namespace {

using nlohmann::json;

// "text" with its quotes. Built by appending: GCC 12 warns (-Wrestrict, a false positive) on
// "\"" + std::string(...) chains.
std::string in_quotes(std::string_view text) {
  std::string q = "\"";
  q.append(text);
  q += '"';
  return q;
}

// Where a message points: the scene file, the key and the map.
struct MapContext {
  const std::string& where;
  const std::string& folder;
  const std::string& name;

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(where + ": key 'maps': map '" + name + "': " + problem);
  }

  double number(const json& object, const char* field) const {
    const auto it = object.find(field);
    if (it == object.end()) fail(std::string("missing \"") + field + "\"");
    if (!it->is_number()) fail(std::string("\"") + field + "\" = " + it->dump() + " must be a number");
    const double x = it->get<double>();
    if (!std::isfinite(x)) fail(std::string("\"") + field + "\" must be finite");
    return x;
  }

  std::optional<double> optional_number(const json& object, const char* field) const {
    if (!object.contains(field) || object.at(field).is_null()) return std::nullopt;
    return number(object, field);
  }

  std::string text(const json& object, const char* field) const {
    const auto it = object.find(field);
    if (it == object.end()) fail(std::string("missing \"") + field + "\"");
    if (!it->is_string() || it->get<std::string>().empty())
      fail(std::string("\"") + field + "\" = " + it->dump() + " must be a non-empty string");
    return it->get<std::string>();
  }

  Eigen::Vector3d point(const json& object, const char* field) const {
    const auto it = object.find(field);
    if (it == object.end()) fail(std::string("missing \"") + field + "\"");
    if (!it->is_array() || it->size() != 3 || !std::all_of(it->begin(), it->end(), [](const json& v) { return v.is_number(); }))
      fail(std::string("\"") + field + "\" = " + it->dump() + " must be three numbers [x, y, z]");
    Eigen::Vector3d p((*it)[0].get<double>(), (*it)[1].get<double>(), (*it)[2].get<double>());
    if (!p.allFinite()) fail(std::string("\"") + field + "\" must be finite");
    return p;
  }

  // A file path relative to the scene's folder, which must exist now (before anything is built).
  std::string file(const json& object, const char* field) const {
    const std::string given = text(object, field);
    std::filesystem::path path(given);
    if (path.is_relative()) path = std::filesystem::path(folder) / path;
    path = path.lexically_normal();
    if (!std::filesystem::is_regular_file(path))
      fail(std::string("\"") + field + "\" = \"" + given + "\": file not found (looked for " + path.string() + ")");
    return path.string();
  }

  MapOperand operand(const json& value, const std::string& what) const {
    if (value.is_number()) {
      if (!std::isfinite(value.get<double>())) fail(what + " must be finite");
      return value.get<double>();
    }
    if (value.is_string() && !value.get<std::string>().empty()) return value.get<std::string>();
    fail(what + " = " + value.dump() + " must be a map (a name or a definition) or a number");
  }

  // Only the fields in `allowed` may appear.
  void only(const json& object, std::initializer_list<std::string_view> allowed) const {
    for (auto it = object.begin(); it != object.end(); ++it)
      if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end()) {
        std::string list;
        for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + in_quotes(a);
        fail("unknown field \"" + it.key() + "\" (this source takes " + list + ")");
      }
  }
};

// {"points": [[A, B], ...], "radius": r}: each entry a segment from point A to point B.
SegmentsRegion segments_region(const json& shape, const MapContext& c) {
  SegmentsRegion s;
  s.radius = c.number(shape, "radius");
  if (!(s.radius >= 0.0)) c.fail("segments \"radius\" must be >= 0");
  const auto points = shape.find("points");
  if (points == shape.end() || !points->is_array() || points->empty())
    c.fail("segments \"points\" must be a non-empty list of [[x, y, z], [x, y, z]] pairs");
  for (size_t i = 0; i < points->size(); ++i) {
    const json& pair = (*points)[i];
    if (!pair.is_array() || pair.size() != 2)
      c.fail("segments \"points\"[" + std::to_string(i) + "] = " + pair.dump() + " must be a pair [[x, y, z], [x, y, z]]");
    const json ends = {{"from", pair[0]}, {"to", pair[1]}};
    s.segments.emplace_back(c.point(ends, "from"), c.point(ends, "to"));
  }
  return s;
}

RegionSource region_source(const json& object, const MapContext& c, std::string_view key) {
  RegionSource r;
  if (auto falloff = c.optional_number(object, "falloff")) {
    if (*falloff < 0.0) c.fail("\"falloff\" = " + std::to_string(*falloff) + " must be >= 0");
    r.falloff = *falloff;
  }
  const json& shape = object.at(std::string(key));
  if (!shape.is_object()) c.fail("\"" + std::string(key) + "\" must be an object");
  if (key == "sphere") {
    c.only(shape, {"center", "radius"});
    SphereRegion s{c.point(shape, "center"), c.number(shape, "radius")};
    if (!(s.radius >= 0.0)) c.fail("sphere \"radius\" must be >= 0");
    r.region = s;
  } else if (key == "box") {
    c.only(shape, {"min", "max"});
    BoxRegion b{c.point(shape, "min"), c.point(shape, "max")};
    if ((b.min.array() > b.max.array()).any()) c.fail("box \"min\" must not exceed \"max\" on any axis");
    r.region = b;
  } else if (key == "segments") {
    c.only(shape, {"points", "radius"});
    r.region = segments_region(shape, c);
  } else {
    c.only(shape, {"point", "normal"});
    HalfSpaceRegion h{c.point(shape, "point"), c.point(shape, "normal")};
    if (!(h.normal.norm() > 0.0)) c.fail("half_space \"normal\" must not be zero");
    h.normal.normalize();
    r.region = h;
  }
  return r;
}

std::vector<MapOperand> operand_list(const json& value, const MapContext& c, std::string_view key) {
  if (!value.is_array() || value.empty())
    c.fail(in_quotes(key) + " = " + value.dump() + " must be a non-empty list of map names or numbers");
  std::vector<MapOperand> operands;
  for (size_t i = 0; i < value.size(); ++i)
    operands.push_back(c.operand(value[i], in_quotes(key) + "[" + std::to_string(i) + "]"));
  return operands;
}

// ---- map tools' fields ------------------------------------------------------------------------------

// A time that must be positive: "time" of "diffuse" and "elevation".
double positive_time(const json& object, const MapContext& c) {
  const double time = c.number(object, "time");
  if (!(time > 0.0)) c.fail("\"time\" = " + object.at("time").dump() + " must be > 0");
  return time;
}

// An optional step count >= 1 (default 1).
int step_count(const json& object, const MapContext& c) {
  const auto it = object.find("steps");
  if (it == object.end()) return 1;
  if (!it->is_number_integer() || it->get<long long>() < 1 || it->get<long long>() > 1000000)
    c.fail("\"steps\" = " + it->dump() + " must be a whole number from 1 to 1000000");
  return static_cast<int>(it->get<long long>());
}

// The operand of "gradient" and "slope": a scalar map, by name or inline (a number has no gradient).
MapOperand map_name_operand(const json& object, const MapContext& c, const char* key) {
  const json& value = object.at(key);
  if (!value.is_string() || value.get<std::string>().empty())
    c.fail(in_quotes(key) + " = " + value.dump() + " must be a scalar map (its name or its definition; a constant has no gradient)");
  return value.get<std::string>();
}

LaplaceSource laplace_source(const json& list, const MapContext& c) {
  const std::string shape = "(expected [{\"region\": MAP, \"value\": v}, ...])";
  if (!list.is_array() || list.empty()) c.fail("\"laplace\" = " + list.dump() + " must be a non-empty list of regions " + shape);
  LaplaceSource s;
  for (size_t i = 0; i < list.size(); ++i) {
    const json& entry = list[i];
    const std::string at = "\"laplace\"[" + std::to_string(i) + "]";
    if (!entry.is_object()) c.fail(at + " = " + entry.dump() + " must be an object " + shape);
    for (auto it = entry.begin(); it != entry.end(); ++it)
      if (it.key() != "region" && it.key() != "value")
        c.fail(at + ": unknown field \"" + it.key() + "\" (a region takes \"region\" and \"value\")");
    if (!entry.contains("region") || !entry.at("region").is_string() || entry.at("region").get<std::string>().empty())
      c.fail(at + ": \"region\" must be a scalar map, by name or inline (its vertices with value >= 0.5 are held)");
    s.regions.push_back(LaplaceRegion{entry.at("region").get<std::string>(), c.number(entry, "value")});
  }
  return s;
}

// ---- the source table: one row per source kind, told apart by its defining key ---------------------

struct SourceKind {
  std::string_view key;  // the field that says which source this is
  MapKind kind;
  std::function<MapSource(const json& object, const MapContext&)> parse;
};

const std::vector<SourceKind>& source_kinds() {
  static const std::vector<SourceKind> kinds = {
      {"texture", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"texture", "channel"});
         const std::string channel = c.text(o, "channel");
         static const std::map<std::string, TextureChannel> channels = {{"r", TextureChannel::Red},
                                                                         {"g", TextureChannel::Green},
                                                                         {"b", TextureChannel::Blue},
                                                                         {"a", TextureChannel::Alpha},
                                                                         {"luma", TextureChannel::Luma}};
         const auto it = channels.find(channel);
         if (it == channels.end()) c.fail("\"channel\" = \"" + channel + "\" must be \"r\", \"g\", \"b\", \"a\" or \"luma\"");
         return TextureSource{c.file(o, "texture"), it->second};
       }},
      {"sphere", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"sphere", "falloff"});
         return region_source(o, c, "sphere");
       }},
      {"box", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"box", "falloff"});
         return region_source(o, c, "box");
       }},
      {"half_space", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"half_space", "falloff"});
         return region_source(o, c, "half_space");
       }},
      {"segments", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"segments", "falloff"});
         return region_source(o, c, "segments");
       }},
      {"axis", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"axis"});
         const std::string axis = c.text(o, "axis");
         if (axis != "x" && axis != "y" && axis != "z") c.fail("\"axis\" = \"" + axis + "\" must be \"x\", \"y\" or \"z\"");
         return AxisRampSource{axis[0] - 'x'};
       }},
      {"map", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"map", "range"});
         const auto range = o.find("range");
         if (range == o.end()) c.fail("missing \"range\" ({\"map\": NAME, \"range\": [lo, hi]})");
         if (!range->is_array() || range->size() != 2 || !(*range)[0].is_number() || !(*range)[1].is_number())
           c.fail("\"range\" = " + range->dump() + " must be two numbers [lo, hi]");
         return RangeSource{c.operand(o.at("map"), "\"map\""), (*range)[0].get<double>(), (*range)[1].get<double>()};
       }},
      {"invert", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"invert"});
         return InvertSource{c.operand(o.at("invert"), "\"invert\"")};
       }},
      {"threshold", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"threshold", "at"});
         return ThresholdSource{c.operand(o.at("threshold"), "\"threshold\""), c.number(o, "at")};
       }},
      {"clamp", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"clamp", "min", "max"});
         ClampSource s{c.operand(o.at("clamp"), "\"clamp\""), c.optional_number(o, "min"), c.optional_number(o, "max")};
         if (!s.low && !s.high) c.fail("\"clamp\" needs \"min\", \"max\" or both");
         if (s.low && s.high && *s.low > *s.high) c.fail("\"min\" must not exceed \"max\"");
         return s;
       }},
      {"sum", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"sum"});
         return CombineSource{CombineOperation::Sum, operand_list(o.at("sum"), c, "sum")};
       }},
      {"product", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"product"});
         return CombineSource{CombineOperation::Product, operand_list(o.at("product"), c, "product")};
       }},
      {"min", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"min"});
         return CombineSource{CombineOperation::Min, operand_list(o.at("min"), c, "min")};
       }},
      {"max", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"max"});
         return CombineSource{CombineOperation::Max, operand_list(o.at("max"), c, "max")};
       }},
      {"direction", MapKind::Vector,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"direction"});
         const Eigen::Vector3d d = c.point(o, "direction");
         if (!(d.norm() > 0.0)) c.fail("\"direction\" must not be zero");
         return DirectionSource{d};
       }},
      {"toward", MapKind::Vector,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"toward"});
         return RadialSource{c.point(o, "toward"), true};
       }},
      {"away_from", MapKind::Vector,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"away_from"});
         return RadialSource{c.point(o, "away_from"), false};
       }},
      {"geodesic_distance", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"geodesic_distance", "method", "time_factor"});
         return parse_geodesic_distance_source(o, c.where + ": key 'maps': map '" + c.name + "'");
       }},
      {"diffuse", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"diffuse", "time", "steps"});
         return DiffuseSource{c.operand(o.at("diffuse"), "\"diffuse\""), positive_time(o, c), step_count(o, c)};
       }},
      {"laplace", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"laplace"});
         return laplace_source(o.at("laplace"), c);
       }},
      {"elevation", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"elevation"});
         const json& flow = o.at("elevation");
         if (!flow.is_object()) c.fail("\"elevation\" = " + flow.dump() + " must be an object ({\"time\": t, \"steps\": n})");
         c.only(flow, {"time", "steps"});
         return ElevationSource{positive_time(flow, c), step_count(flow, c)};
       }},
      {"slope", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"slope"});
         return SlopeSource{map_name_operand(o, c, "slope")};
       }},
      {"gradient", MapKind::Vector,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"gradient", "normalize"});
         GradientSource s{map_name_operand(o, c, "gradient")};
         if (const auto it = o.find("normalize"); it != o.end()) {
           if (!it->is_boolean()) c.fail("\"normalize\" = " + it->dump() + " must be true or false");
           s.normalize = it->get<bool>();
         }
         return s;
       }},
      {"fields_full", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"fields_full", "property"});
         return FieldsFullSource{c.file(o, "fields_full"), c.text(o, "property")};
       }},
      // "ply" comes in two kinds, told apart by the second field (see source_kind_of).
      {"ply", MapKind::Scalar,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"ply", "property"});
         return PlyVertexSource{c.file(o, "ply"), c.text(o, "property")};
       }},
      {"ply", MapKind::Vector,
       [](const json& o, const MapContext& c) -> MapSource {
         c.only(o, {"ply", "face_property"});
         return PlyFaceVectorSource{c.file(o, "ply"), c.text(o, "face_property")};
       }},
  };
  return kinds;
}

std::string known_sources() {
  std::string list;
  for (const SourceKind& k : source_kinds())
    if (list.find(in_quotes(k.key)) == std::string::npos) list += (list.empty() ? "" : ", ") + in_quotes(k.key);
  return "a number or an object with one of " + list;
}

// Which row parses `object`. "clamp" also has "min"/"max" fields, so it is looked for first; any
// other object must name exactly one source.
const SourceKind& source_kind_of(const json& object, const MapContext& c) {
  std::vector<const SourceKind*> found;
  for (const SourceKind& k : source_kinds())
    if (object.contains(std::string(k.key)) && (found.empty() || found.back()->key != k.key)) found.push_back(&k);
  if (object.contains("clamp"))
    found.erase(std::remove_if(found.begin(), found.end(), [](const SourceKind* k) { return k->key == "min" || k->key == "max"; }),
                found.end());
  if (found.empty()) {
    std::string keys;
    for (auto it = object.begin(); it != object.end(); ++it) keys += (keys.empty() ? "" : ", ") + in_quotes(it.key());
    c.fail("{" + keys + "} is no known map source (expected " + known_sources() + ")");
  }
  if (found.size() > 1)
    c.fail("names two sources at once (\"" + std::string(found[0]->key) + "\" and \"" + std::string(found[1]->key) + "\")");
  if (found.front()->key == "ply") {
    const bool face = object.contains("face_property");
    for (const SourceKind& k : source_kinds())
      if (k.key == "ply" && (k.kind == MapKind::Vector) == face) return k;
  }
  return *found.front();
}

// A PLY property name (maps.ply writes every map under its name): letters, digits, '_' and '-'.
bool usable_map_name(const std::string& name) {
  if (name.empty()) return false;
  for (const char ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') return false;
  for (const char* taken : {"x", "y", "z", "red", "green", "blue"})
    if (name == taken) return false;
  return true;
}

}  // namespace

const char* to_string(MapKind kind) { return kind == MapKind::Scalar ? "scalar" : "vector"; }

std::vector<std::string> MapDefinition::dependencies() const {
  std::vector<std::string> names;
  auto add = [&](const MapOperand& operand) {
    if (const auto* name = std::get_if<std::string>(&operand)) names.push_back(*name);
  };
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (requires { s.operand; }) add(s.operand);
        if constexpr (std::is_same_v<S, CombineSource>)
          for (const MapOperand& operand : s.operands) add(operand);
        if constexpr (requires { s.map_dependencies(); })
          for (const std::string& name : s.map_dependencies()) names.push_back(name);
      },
      source);
  return names;
}

const MapDefinition* MapSet::find(const std::string& name) const {
  for (const MapDefinition& m : maps_)
    if (m.name == name) return &m;
  return nullptr;
}

MapSet parse_maps(const json& given, const std::string& folder, const std::string& where) {
  if (given.is_null()) return {};
  if (!given.is_object())
    throw InputError(where + ": key 'maps' = " + given.dump() + " must be an object of named maps ({\"NAME\": SOURCE, ...})");
  const json maps = with_inline_maps_named(given);

  std::map<std::string, MapDefinition> by_name;
  std::vector<std::string> file_order;
  for (auto it = maps.begin(); it != maps.end(); ++it) {
    const std::string& name = it.key();
    const MapContext c{where, folder, name};
    if (!usable_map_name(name))
      c.fail("the name must be letters, digits, '_' and '-' (it becomes a PLY property name) and not x, y, z, red, green, blue");
    MapDefinition d;
    d.name = name;
    const json& value = it.value();
    if (value.is_number()) {
      d.source = ConstantSource{value.get<double>()};
    } else if (value.is_object()) {
      const SourceKind& kind = source_kind_of(value, c);
      d.kind = kind.kind;
      d.source = kind.parse(value, c);
    } else {
      c.fail(value.dump() + " is no known map source (expected " + known_sources() + ")");
    }
    file_order.push_back(name);
    by_name.emplace(name, std::move(d));
  }

  // A vector map is written as NAME_x, NAME_y, NAME_z (maps.ply): no other map may be called so.
  for (const std::string& name : file_order) {
    if (by_name.at(name).kind != MapKind::Vector) continue;
    for (const char axis : {'x', 'y', 'z'}) {
      std::string component = name;
      component += '_';
      component += axis;
      if (by_name.count(component))
        MapContext{where, folder, component}.fail("the name is taken by the component " + component +
                                                  " of the vector map '" + name + "' (maps.ply writes both)");
    }
  }

  // Operands must name scalar maps.
  for (const std::string& name : file_order) {
    const MapContext c{where, folder, name};
    for (const std::string& dependency : by_name.at(name).dependencies()) {
      const auto it = by_name.find(dependency);
      if (it == by_name.end()) c.fail("reads map '" + dependency + "', which is not defined in 'maps'");
      if (it->second.kind != MapKind::Scalar)
        c.fail("reads map '" + dependency + "', a vector map, where a scalar map is needed");
    }
  }

  // Depth-first topological sort; a map met again while still open closes a cycle.
  std::vector<MapDefinition> ordered;
  std::map<std::string, int> state;  // 0 unseen, 1 open, 2 done
  std::vector<std::string> path;
  std::function<void(const std::string&)> visit = [&](const std::string& name) {
    if (state[name] == 2) return;
    if (state[name] == 1) {
      std::string cycle;
      for (auto p = std::find(path.begin(), path.end(), name); p != path.end(); ++p) cycle += *p + " -> ";
      MapContext{where, folder, name}.fail("the maps read each other in a cycle (" + cycle + name + ")");
    }
    state[name] = 1;
    path.push_back(name);
    for (const std::string& dependency : by_name.at(name).dependencies()) visit(dependency);
    path.pop_back();
    state[name] = 2;
    ordered.push_back(by_name.at(name));
  };
  for (const std::string& name : file_order) visit(name);
  return MapSet(std::move(ordered));
}

}  // namespace physarum
