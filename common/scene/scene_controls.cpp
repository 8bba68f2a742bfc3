#include "common/scene/scene_controls.hpp"

#include "common/base/value_range.hpp"
#include "common/scene/scene_fields.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

namespace physarum {
namespace {

using nlohmann::json;

// A field of one entry of a list key ("read_stimuli"[0].weight): present, and a number / a map name.
double finite_number(const json& entry, const char* field, const std::string& source, const std::string& key) {
  const auto it = entry.find(field);
  if (it == entry.end()) fail_key(source, key, std::string("missing \"") + field + "\"");
  if (!it->is_number()) fail_key(source, key, std::string("\"") + field + "\" = " + it->dump() + " must be a number");
  return it->get<double>();
}

std::string map_name(const json& entry, const char* field, const std::string& source, const std::string& key) {
  const auto it = entry.find(field);
  if (it == entry.end()) fail_key(source, key, std::string("missing \"") + field + "\" (a map name)");
  if (!it->is_string() || it->get<std::string>().empty())
    fail_key(source, key, std::string("\"") + field + "\" = " + it->dump() + " must be a map name");
  return it->get<std::string>();
}

// A scalar operand's map, when it is one, exists and is scalar.
void check_operand(const MapSet& maps, const std::string& source, const std::string& key, const MapOperand& operand) {
  if (const auto* name = std::get_if<std::string>(&operand)) check_map_reference(maps, source, key, *name, MapKind::Scalar);
}

}  // namespace

SceneControls read_controls(const json& j, const std::string& source) {
  SceneControls c;
  for (const char* key : {"read_stimuli", "write_stimuli"}) {
    const auto it = j.find(key);
    if (it == j.end() || it->is_null()) continue;
    if (!it->is_array()) fail_key(source, key, it->dump() + " must be a list of {\"map\": NAME, ...}");
    const bool read = std::string_view(key) == "read_stimuli";
    for (size_t i = 0; i < it->size(); ++i) {
      const std::string name = entry_name(key, i);
      const json& entry = (*it)[i];
      only_fields(entry, {"map", read ? "weight" : "rate"}, source, name);
      if (read)
        c.read_stimuli.push_back({map_name(entry, "map", source, name), finite_number(entry, "weight", source, name)});
      else
        c.write_stimuli.push_back({map_name(entry, "map", source, name), finite_number(entry, "rate", source, name)});
    }
  }
  if (const auto it = j.find("spawn_weight"); it != j.end() && !it->is_null())
    c.spawn_weight = field_operand(*it, source, "spawn_weight");
  if (const auto it = j.find("bias"); it != j.end() && !it->is_null()) {
    only_fields(*it, {"direction", "strength", "symmetry"}, source, "bias");
    BiasSpec b;
    b.direction = map_name(*it, "direction", source, "bias");
    const auto strength = it->find("strength");
    if (strength == it->end()) fail_key(source, "bias", "missing \"strength\" (deg/s: a number or a map name)");
    b.strength = field_operand(*strength, source, "bias");
    if (const auto symmetry = it->find("symmetry"); symmetry != it->end()) {
      if (!symmetry->is_number_integer()) fail_key(source, "bias", "\"symmetry\" = " + symmetry->dump() + " must be a whole number 1..8");
      b.symmetry = symmetry->get<int>();
    }
    c.bias = b;
  }
  const SceneReader read{j, source};
  if (auto heading = read.string("spawn_heading")) {
    if (*heading == "random") c.spawn_heading = SpawnHeading::Random;
    else if (*heading == "bias") c.spawn_heading = SpawnHeading::Bias;
    else fail_key(source, "spawn_heading", "\"" + *heading + "\" must be \"random\" or \"bias\"");
  }
  if (auto boundary = read.string("boundary")) {
    if (*boundary == "reflect") c.boundary = BoundaryBehaviour::Reflect;
    else if (*boundary == "terminate") c.boundary = BoundaryBehaviour::Terminate;
    else fail_key(source, "boundary", "\"" + *boundary + "\" must be \"reflect\" or \"terminate\"");
  }
  return c;
}

void validate_controls(const SceneControls& c, const MapSet& maps, const std::string& s) {
  for (size_t i = 0; i < c.read_stimuli.size(); ++i) {
    const std::string key = entry_name("read_stimuli", i);
    check_map_reference(maps, s, key, c.read_stimuli[i].map, MapKind::Scalar);
    if (!std::isfinite(c.read_stimuli[i].weight)) fail_key(s, key, "\"weight\" must be finite");
  }
  for (size_t i = 0; i < c.write_stimuli.size(); ++i) {
    const std::string key = entry_name("write_stimuli", i);
    check_map_reference(maps, s, key, c.write_stimuli[i].map, MapKind::Scalar);
    if (!std::isfinite(c.write_stimuli[i].rate)) fail_key(s, key, "\"rate\" must be finite");
  }
  if (c.spawn_weight) {
    check_operand(maps, s, "spawn_weight", *c.spawn_weight);
    if (const auto* w = std::get_if<double>(&*c.spawn_weight)) {
      if (!(*w >= 0.0) || !std::isfinite(*w)) fail_key(s, "spawn_weight", ValueRange::number(*w) + " must be >= 0");
      if (*w == 0.0) fail_key(s, "spawn_weight", "0 everywhere: no agent could be placed (all spawn weights are zero)");
    }
  }
  if (c.bias) {
    check_map_reference(maps, s, "bias", c.bias->direction, MapKind::Vector);
    check_operand(maps, s, "bias", c.bias->strength);
    if (const auto* strength = std::get_if<double>(&c.bias->strength); strength && !(*strength >= 0.0 && std::isfinite(*strength)))
      fail_key(s, "bias", "\"strength\" = " + ValueRange::number(*strength) + " deg/s must be >= 0");
    if (c.bias->symmetry < 1 || c.bias->symmetry > 8)
      fail_key(s, "bias", "\"symmetry\" = " + std::to_string(c.bias->symmetry) + " must be 1..8");
  }
  if (c.spawn_heading == SpawnHeading::Bias && !c.bias)
    fail_key(s, "spawn_heading", "\"bias\" aligns agents with the bias direction, and the scene has no 'bias'");
}

}  // namespace physarum
