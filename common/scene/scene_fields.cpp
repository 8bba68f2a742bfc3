#include "common/scene/scene_fields.hpp"

#include "common/base/errors.hpp"
#include "common/scene/scene_keys.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace physarum {
namespace {

using nlohmann::json;

const SceneKey& spec_of(std::string_view name) {
  if (const SceneKey* k = find_scene_key(name)) return *k;
  throw std::logic_error("scene: no spec for key " + std::string(name));
}

}  // namespace

void fail_nesting(const std::string& where) {
  throw InputError(where + ": nested deeper than " + std::to_string(kMaxSceneNesting) +
                   " levels of objects and arrays (a scene allows at most " + std::to_string(kMaxSceneNesting) +
                   "; is a map definition nested by mistake?)");
}

void check_scene_nesting(const json& value, const std::string& where) {
  // Depth-first with an explicit stack: a recursive walk would itself be what a deep value breaks.
  std::vector<std::pair<const json*, int>> todo = {{&value, 1}};
  while (!todo.empty()) {
    const auto [node, depth] = todo.back();
    todo.pop_back();
    if (!node->is_structured()) continue;
    if (depth > kMaxSceneNesting) fail_nesting(where);
    for (const json& child : *node) todo.emplace_back(&child, depth + 1);
  }
}

std::string scene_where(const std::string& source) { return source.empty() ? std::string("scene") : source; }

void fail_key(const std::string& source, std::string_view key, const std::string& problem) {
  throw InputError(scene_where(source) + ": key '" + std::string(key) + "': " + problem);
}

void fail_range(const std::string& source, std::string_view key, const std::string& shown_value,
                const ValueRange& range) {
  throw InputError(scene_where(source) + ": key '" + std::string(key) + "' = " + shown_value + " is out of range (" +
                   range.describe() + ")");
}

void check_range(const std::string& source, std::string_view key, double file_units_value) {
  const ValueRange& range = spec_of(key).range;
  if (!range.contains(file_units_value)) fail_range(source, key, ValueRange::number(file_units_value), range);
}

void only_fields(const json& entry, std::initializer_list<const char*> allowed, const std::string& source,
                 std::string_view key) {
  if (!entry.is_object()) fail_key(source, key, entry.dump() + " must be an object");
  for (auto it = entry.begin(); it != entry.end(); ++it)
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return it.key() == a; })) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "\"" : ", \"") + std::string(a) + "\"";
      fail_key(source, key, "unknown field \"" + it.key() + "\" (it takes " + list + ")");
    }
}

std::string entry_name(std::string_view key, size_t index) { return std::string(key) + "[" + std::to_string(index) + "]"; }

double field_number(const json& v, const std::string& source, const std::string& key) {
  if (!v.is_number()) fail_key(source, key, v.dump() + " must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail_key(source, key, v.dump() + " must be finite");
  return x;
}

std::string field_map_name(const json& v, const std::string& source, const std::string& key) {
  if (!v.is_string() || v.get<std::string>().empty()) fail_key(source, key, v.dump() + " must be a map name");
  return v.get<std::string>();
}

MapOperand field_operand(const json& v, const std::string& source, const std::string& key) {
  if (v.is_number()) return field_number(v, source, key);
  if (v.is_string() && !v.get<std::string>().empty()) return v.get<std::string>();
  fail_key(source, key, v.dump() + " must be a number or a scalar map name");
}

void check_map_reference(const MapSet& maps, const std::string& source, const std::string& key,
                         const std::string& name, MapKind kind, const std::string& shown_value) {
  const MapDefinition* map = maps.find(name);
  if (!map) {
    std::string known;
    for (const MapDefinition& m : maps.in_dependency_order()) known += (known.empty() ? "" : ", ") + m.name;
    throw InputError(scene_where(source) + ": key '" + key + "'" + (shown_value.empty() ? "" : " = " + shown_value) +
                     ": map '" + name + "' is not defined in 'maps' (" +
                     (known.empty() ? "no maps are defined" : "defined: " + known) + ")");
  }
  if (map->kind != kind)
    fail_key(source, key, "map '" + name + "' is a " + to_string(map->kind) + " map, but a " + to_string(kind) +
                              " map is needed here");
}

const json* SceneReader::find(std::string_view key) const {
  auto it = object.find(std::string(key));
  if (it == object.end()) {
    if (spec_of(key).required) throw InputError(scene_where(source) + ": required key '" + std::string(key) + "' is missing");
    return nullptr;
  }
  return &*it;
}

void SceneReader::wrong_type(std::string_view key, const json& v, const char* expected) const {
  throw InputError(scene_where(source) + ": key '" + std::string(key) + "' = " + v.dump() + " has the wrong type (" +
                   v.type_name() + "; expected " + expected + ")");
}

std::optional<double> SceneReader::number(std::string_view key) const {
  const json* v = find(key);
  if (!v) return std::nullopt;
  const SceneKey& spec = spec_of(key);
  if (v->is_null() && (spec.kind == KeyKind::NumberOrNull || !spec.required)) return std::nullopt;
  if (!v->is_number()) wrong_type(key, *v, spec.kind == KeyKind::NumberOrNull ? "a number or null" : "a number");
  const double x = v->get<double>();
  if (!spec.range.contains(x)) fail_range(source, key, v->dump(), spec.range);
  return x;
}

std::optional<long long> SceneReader::integer(std::string_view key) const {
  const json* v = find(key);
  if (!v) return std::nullopt;
  const SceneKey& spec = spec_of(key);
  if (v->is_null() && !spec.required) return std::nullopt;
  if (!v->is_number()) wrong_type(key, *v, "an integer");
  const double x = v->get<double>();
  if (!spec.range.contains(x)) fail_range(source, key, v->dump(), spec.range);
  if (v->is_number_float() && x != std::floor(x))
    throw InputError(scene_where(source) + ": key '" + std::string(key) + "' = " + v->dump() +
                     " must be a whole number (" + spec.range.describe() + ")");
  return v->is_number_unsigned() ? static_cast<long long>(v->get<unsigned long long>())
         : v->is_number_integer() ? v->get<long long>()
                                  : static_cast<long long>(x);
}

std::optional<std::string> SceneReader::string(std::string_view key) const {
  const json* v = find(key);
  if (!v) return std::nullopt;
  if (v->is_null() && !spec_of(key).required) return std::nullopt;
  if (!v->is_string()) wrong_type(key, *v, "a string");
  return v->get<std::string>();
}

}  // namespace physarum
