#include "common/scene/scene.hpp"

#include "common/scene/scene_fields.hpp"
#include "common/scene/scene_overrides.hpp"

#include "common/base/errors.hpp"
#include "common/scene/scene_keys.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

namespace physarum {
namespace {

using nlohmann::json;

const SceneKey& spec_of(std::string_view name) {
  if (const SceneKey* k = find_scene_key(name)) return *k;
  throw std::logic_error("scene: no spec for key " + std::string(name));
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

[[noreturn]] void fail_range(const std::string& source, std::string_view key, const std::string& shown_value,
                             const ValueRange& range) {
  throw InputError(scene_where(source) + ": key '" + std::string(key) + "' = " + shown_value + " is out of range (" +
                   range.describe() + ")");
}

void check_range(const std::string& source, std::string_view key, double file_units_value) {
  const ValueRange& range = spec_of(key).range;
  if (!range.contains(file_units_value)) fail_range(source, key, ValueRange::number(file_units_value), range);
}

// ---- reading one value from the JSON object, with its type and range checked ----------------------

struct Reader {
  const json& object;
  const std::string& source;

  const json* find(std::string_view key) const {
    auto it = object.find(std::string(key));
    if (it == object.end()) {
      if (spec_of(key).required)
        throw InputError(scene_where(source) + ": required key '" + std::string(key) + "' is missing");
      return nullptr;
    }
    return &*it;
  }

  [[noreturn]] void wrong_type(std::string_view key, const json& v, const char* expected) const {
    throw InputError(scene_where(source) + ": key '" + std::string(key) + "' = " + v.dump() + " has the wrong type (" +
                     v.type_name() + "; expected " + expected + ")");
  }

  // A number, range-checked against the spec; returns nullopt when absent (optional keys) or null
  // (keys that allow it; null is treated as "not given" for optional keys too).
  std::optional<double> number(std::string_view key) const {
    const json* v = find(key);
    if (!v) return std::nullopt;
    const SceneKey& spec = spec_of(key);
    if (v->is_null() && (spec.kind == KeyKind::NumberOrNull || !spec.required)) return std::nullopt;
    if (!v->is_number())
      wrong_type(key, *v, spec.kind == KeyKind::NumberOrNull ? "a number or null" : "a number");
    const double x = v->get<double>();
    if (!spec.range.contains(x)) fail_range(source, key, v->dump(), spec.range);
    return x;
  }

  // An integer; a float with an integral value (1e5) is accepted, 2.5 is not.
  std::optional<long long> integer(std::string_view key) const {
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

  std::optional<std::string> string(std::string_view key) const {
    const json* v = find(key);
    if (!v) return std::nullopt;
    if (v->is_null() && !spec_of(key).required) return std::nullopt;
    if (!v->is_string()) wrong_type(key, *v, "a string");
    return v->get<std::string>();
  }
};

// The keys of the agent model alone: its count, its parameters (Table 1), the controls and species.
std::vector<std::string> agent_model_keys() {
  std::vector<std::string> keys = {"agents", "read_stimuli", "write_stimuli", "spawn_weight", "bias",
                                   "spawn_heading", "boundary", "species", "sensing"};
  for (const ParameterSpec& p : kParameterTable) keys.emplace_back(p.key);
  return keys;
}

// ---- maps and controls ------------------------------------------------------------------------------


// A parameter given by a map: a bare map name, or {"map": NAME, "range": [lo, hi]} whose bounds are
// in the parameter's range (so every map value in 0..1 gives an allowed value). nullopt for a
// number (or null, or absent): the ordinary reader takes those.
// `key` names it in messages: p.key at the top level, "species[i].key" inside a species entry.
std::optional<ParameterMap> read_parameter_map(const json& object, const ParameterSpec& p, const std::string& source,
                                              std::string_view key) {
  const auto it = object.find(std::string(p.key));
  if (it == object.end()) return std::nullopt;
  if (it->is_string()) {
    if (it->get<std::string>().empty()) fail_key(source, key, "an empty map name");
    return ParameterMap{it->get<std::string>(), std::nullopt};
  }
  if (!it->is_object()) return std::nullopt;
  for (auto field = it->begin(); field != it->end(); ++field)
    if (field.key() != "map" && field.key() != "range")
      fail_key(source, key, "unknown field \"" + field.key() + "\" (a parameter map is {\"map\": NAME, \"range\": [lo, hi]})");
  const auto name = it->find("map");
  if (name == it->end() || !name->is_string() || name->get<std::string>().empty())
    fail_key(source, key, it->dump() + " needs \"map\": the name of a scalar map");
  ParameterMap map{name->get<std::string>(), std::nullopt};
  if (const auto range = it->find("range"); range != it->end()) {
    if (!range->is_array() || range->size() != 2 || !(*range)[0].is_number() || !(*range)[1].is_number())
      fail_key(source, key, "\"range\" = " + range->dump() + " must be two numbers [lo, hi]");
    map.range = std::array<double, 2>{(*range)[0].get<double>(), (*range)[1].get<double>()};
    for (const double bound : *map.range)
      if (!map_value_range(p).contains(bound))
        fail_key(source, key, "\"range\" = " + range->dump() + ": the bound " + ValueRange::number(bound) + " " +
                                    std::string(p.unit) + " is out of range (" + map_value_range(p).describe() + ")");
  }
  return map;
}

// A field of one entry of a list key ("read_stimuli"[0].weight).
std::string entry_name(std::string_view key, size_t index) { return std::string(key) + "[" + std::to_string(index) + "]"; }

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


// A map name or a number.
MapOperand operand_value(const json& value, const std::string& source, const std::string& key) {
  if (value.is_number()) return value.get<double>();
  if (value.is_string() && !value.get<std::string>().empty()) return value.get<std::string>();
  fail_key(source, key, value.dump() + " must be a number or a map name");
}

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
    c.spawn_weight = operand_value(*it, source, "spawn_weight");
  if (const auto it = j.find("bias"); it != j.end() && !it->is_null()) {
    only_fields(*it, {"direction", "strength", "symmetry"}, source, "bias");
    BiasSpec b;
    b.direction = map_name(*it, "direction", source, "bias");
    const auto strength = it->find("strength");
    if (strength == it->end()) fail_key(source, "bias", "missing \"strength\" (deg/s: a number or a map name)");
    b.strength = operand_value(*strength, source, "bias");
    if (const auto symmetry = it->find("symmetry"); symmetry != it->end()) {
      if (!symmetry->is_number_integer()) fail_key(source, "bias", "\"symmetry\" = " + symmetry->dump() + " must be a whole number 1..8");
      b.symmetry = symmetry->get<int>();
    }
    c.bias = b;
  }
  const Reader read{j, source};
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

// "species": [{"agents": N, PARAMETER: number | map, ...}, ...] and "sensing": K x K numbers. The
// entries' parameter values are checked like the top-level keys' (validate_species), with messages
// naming "species[i].KEY".
SceneSpecies read_species(const json& j, const std::string& source) {
  SceneSpecies result;
  const auto list = j.find("species");
  const bool given = list != j.end() && !list->is_null();
  if (given) {
    if (!list->is_array() || list->empty())
      fail_key(source, "species", list->dump() + " must be a non-empty list of {\"agents\": N, ...parameter overrides}");
    for (size_t i = 0; i < list->size(); ++i) {
      const std::string name = entry_name("species", i);
      const json& entry = (*list)[i];
      if (!entry.is_object()) fail_key(source, name, entry.dump() + " must be an object");
      SpeciesSpec species;
      for (auto field = entry.begin(); field != entry.end(); ++field) {
        if (field.key() == "agents") continue;
        if (std::none_of(kParameterTable.begin(), kParameterTable.end(), [&](const ParameterSpec& p) { return p.key == field.key(); }))
          fail_key(source, name + "." + field.key(),
                   "unknown field (a species takes \"agents\" and the model parameters of Table 1, e.g. \"" +
                       closest_scene_key(field.key()) + "\")");
      }
      const auto agents = entry.find("agents");
      if (agents == entry.end()) fail_key(source, name, "missing \"agents\" (the number of agents of this species)");
      const std::string agents_key = name + ".agents";
      if (!agents->is_number() || agents->get<double>() != std::floor(agents->get<double>()))
        fail_key(source, agents_key, agents->dump() + " must be a whole number");
      if (!spec_of("agents").range.contains(agents->get<double>()))
        fail_key(source, agents_key, agents->dump() + " is out of range (" + spec_of("agents").range.describe() + ")");
      species.agents = static_cast<int>(agents->get<double>());
      for (const ParameterSpec& p : kParameterTable) {
        const std::string key = name + "." + std::string(p.key);
        const size_t index = static_cast<size_t>(p.id);
        if (auto map = read_parameter_map(entry, p, source, key)) {
          species.parameter_maps[index] = *map;
          continue;
        }
        const auto value = entry.find(std::string(p.key));
        if (value == entry.end()) continue;  // inherits the top-level value
        if (value->is_null() && p.null_means_infinite) {
          species.parameters[index] = kInfinity;
          continue;
        }
        if (!value->is_number())
          fail_key(source, key, value->dump() + " has the wrong type (" + value->type_name() + "; expected a number" +
                                    (p.null_means_infinite ? ", null" : "") + " or a scalar map)");
        species.parameters[index] = value->get<double>() * p.file_to_si;
      }
      result.species.push_back(species);
    }
  }
  if (const auto matrix = j.find("sensing"); matrix != j.end() && !matrix->is_null()) {
    if (!given) fail_key(source, "sensing", "an interaction matrix between species, and the scene has no 'species'");
    const size_t k = result.species.size();
    const std::string shape = std::to_string(k) + " x " + std::to_string(k);
    if (!matrix->is_array() || matrix->size() != k)
      fail_key(source, "sensing", matrix->dump() + " must be a " + shape + " matrix (one row per species)");
    for (size_t row = 0; row < k; ++row) {
      const json& r = (*matrix)[row];
      if (!r.is_array() || r.size() != k)
        fail_key(source, "sensing", "row " + std::to_string(row) + " = " + r.dump() + " must be " + std::to_string(k) +
                                        " numbers (the matrix is " + shape + ")");
      for (size_t col = 0; col < k; ++col) {
        if (!r[col].is_number())
          fail_key(source, "sensing", "[" + std::to_string(row) + "][" + std::to_string(col) + "] = " + r[col].dump() +
                                          " must be a number");
        result.sensing.push_back(r[col].get<double>());
      }
    }
  }
  return result;
}

// The map `name` must exist and be of `kind`. `shown_value` (optional) is shown after the key, as a
// number's out-of-range message shows the number.
void check_map_reference(const Scene& scene, const std::string& key, const std::string& name, MapKind kind,
                         const std::string& shown_value = {}) {
  const MapDefinition* map = scene.maps.find(name);
  if (!map) {
    std::string known;
    for (const MapDefinition& m : scene.maps.in_dependency_order()) known += (known.empty() ? "" : ", ") + m.name;
    throw InputError(scene_where(scene.source) + ": key '" + key + "'" + (shown_value.empty() ? "" : " = " + shown_value) +
                     ": map '" + name + "' is not defined in 'maps' (" +
                     (known.empty() ? "no maps are defined" : "defined: " + known) + ")");
  }
  if (map->kind != kind)
    fail_key(scene.source, key, "map '" + name + "' is a " + to_string(map->kind) + " map, but a " + to_string(kind) +
                                    " map is needed here");
}

void check_operand(const Scene& scene, const std::string& key, const MapOperand& operand) {
  if (const auto* name = std::get_if<std::string>(&operand)) check_map_reference(scene, key, *name, MapKind::Scalar);
}

void validate_controls(const Scene& scene) {
  const std::string& s = scene.source;
  const SceneControls& c = scene.controls;
  for (size_t i = 0; i < c.read_stimuli.size(); ++i) {
    const std::string key = entry_name("read_stimuli", i);
    check_map_reference(scene, key, c.read_stimuli[i].map, MapKind::Scalar);
    if (!std::isfinite(c.read_stimuli[i].weight)) fail_key(s, key, "\"weight\" must be finite");
  }
  for (size_t i = 0; i < c.write_stimuli.size(); ++i) {
    const std::string key = entry_name("write_stimuli", i);
    check_map_reference(scene, key, c.write_stimuli[i].map, MapKind::Scalar);
    if (!std::isfinite(c.write_stimuli[i].rate)) fail_key(s, key, "\"rate\" must be finite");
  }
  if (c.spawn_weight) {
    check_operand(scene, "spawn_weight", *c.spawn_weight);
    if (const auto* w = std::get_if<double>(&*c.spawn_weight)) {
      if (!(*w >= 0.0) || !std::isfinite(*w)) fail_key(s, "spawn_weight", ValueRange::number(*w) + " must be >= 0");
      if (*w == 0.0) fail_key(s, "spawn_weight", "0 everywhere: no agent could be placed (all spawn weights are zero)");
    }
  }
  if (c.bias) {
    check_map_reference(scene, "bias", c.bias->direction, MapKind::Vector);
    check_operand(scene, "bias", c.bias->strength);
    if (const auto* strength = std::get_if<double>(&c.bias->strength); strength && !(*strength >= 0.0 && std::isfinite(*strength)))
      fail_key(s, "bias", "\"strength\" = " + ValueRange::number(*strength) + " deg/s must be >= 0");
    if (c.bias->symmetry < 1 || c.bias->symmetry > 8)
      fail_key(s, "bias", "\"symmetry\" = " + std::to_string(c.bias->symmetry) + " must be 1..8");
  }
  if (c.spawn_heading == SpawnHeading::Bias && !c.bias)
    fail_key(s, "spawn_heading", "\"bias\" aligns agents with the bias direction, and the scene has no 'bias'");
}

// Every species' overrides in their parameter's range (numbers) or naming a scalar map, its agent
// count allowed, and the sensing matrix K x K and finite.
void validate_species(const Scene& scene) {
  const SceneSpecies& sp = scene.species;
  if (!sp.given()) {
    if (!sp.sensing.empty()) fail_key(scene.source, "sensing", "an interaction matrix between species, and the scene has no 'species'");
    return;
  }
  long long total = 0;
  for (size_t i = 0; i < sp.species.size(); ++i) {
    const SpeciesSpec& species = sp.species[i];
    const std::string name = entry_name("species", i);
    check_range(scene.source, "agents", species.agents);  // the same range as the top-level count
    total += species.agents;
    for (const ParameterSpec& p : kParameterTable) {
      const std::string key = name + "." + std::string(p.key);
      const size_t index = static_cast<size_t>(p.id);
      if (const auto& map = species.parameter_maps[index]) {
        check_map_reference(scene, key, map->map, MapKind::Scalar, json(map->map).dump());
        continue;
      }
      if (!species.parameters[index]) continue;
      const double value = *species.parameters[index];
      if (p.null_means_infinite && value == kInfinity) continue;
      const double file_value = value / p.file_to_si;
      if (!p.range.contains(file_value)) fail_range(scene.source, key, ValueRange::number(file_value), p.range);
    }
  }
  if (total != scene.agents)
    fail_key(scene.source, "agents", std::to_string(scene.agents) + " differs from the sum of the species' agents (" +
                                         std::to_string(total) + "); leave it out, or give the sum");
  const size_t k = sp.species.size();
  if (!sp.sensing.empty() && sp.sensing.size() != k * k)
    fail_key(scene.source, "sensing", "has " + std::to_string(sp.sensing.size()) + " entries; a " + std::to_string(k) +
                                          " x " + std::to_string(k) + " matrix has " + std::to_string(k * k));
  for (size_t e = 0; e < sp.sensing.size(); ++e)
    if (!std::isfinite(sp.sensing[e]))
      fail_key(scene.source, "sensing", "[" + std::to_string(e / k) + "][" + std::to_string(e % k) + "] = " +
                                            ValueRange::number(sp.sensing[e]) + " must be finite");
}

json parse_scene_text(const std::string& text, const std::string& path) {
  // Duplicate keys are a likely copy-paste mistake and nlohmann silently keeps the last one, so the
  // parser callback watches the keys of the top-level object.
  std::set<std::string> seen;
  std::string duplicate;
  int depth = 0;
  auto callback = [&](int /*callback_depth*/, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) ++depth;
    if (event == json::parse_event_t::object_end || event == json::parse_event_t::array_end) --depth;
    if (event == json::parse_event_t::key && depth == 1 && duplicate.empty()) {
      const std::string key = parsed.get<std::string>();
      if (!seen.insert(key).second) duplicate = key;
    }
    return true;
  };
  json j;
  try {
    j = json::parse(text, callback);
  } catch (const json::parse_error& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line L, column C: ..."; keep
    // the part after the bracketed id, which carries the line and column.
    std::string message = e.what();
    if (auto pos = message.find("] "); pos != std::string::npos) message = message.substr(pos + 2);
    throw InputError(path + ": malformed JSON: " + message);
  }
  if (!duplicate.empty()) throw InputError(path + ": key '" + duplicate + "' appears more than once");
  if (!j.is_object())
    throw InputError(path + ": a scene must be one JSON object ({...}), found " + std::string(j.type_name()));
  return j;
}

}  // namespace

Scene load_scene(const std::string& path, const nlohmann::json& overrides) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the scene file");
  std::stringstream buffer;
  buffer << file.rdbuf();
  if (file.bad()) throw InputError(path + ": cannot read the scene file");
  json j = parse_scene_text(buffer.str(), path);
  apply_scene_overrides(j, overrides, path);

  for (auto it = j.begin(); it != j.end(); ++it) {
    if (!find_scene_key(it.key()))
      throw InputError(path + ": unknown key '" + it.key() + "' (did you mean '" + closest_scene_key(it.key()) +
                       "'?)");
  }

  const Reader read{j, path};
  Scene scene;
  scene.source = path;
  scene.reaction_diffusion = read_reaction_diffusion(j, path);
  const bool reaction_diffusion = scene.reaction_diffusion.has_value();
  if (reaction_diffusion) {
    // The agent model's keys mean nothing to a reaction-diffusion system: refused rather than
    // silently ignored, so a half-converted scene does not run as something it is not.
    for (const std::string& key : agent_model_keys())
      if (j.contains(key))
        throw InputError(path + ": key '" + key + "' belongs to the agent model (\"physarum\"), and this scene's " +
                         "\"model\" is \"" + scene.reaction_diffusion->model + "\"");
  }

  const std::string mesh = *read.string("mesh");
  if (mesh.empty()) throw InputError(path + ": key 'mesh' = \"\" is empty (give a file path or shape:NAME)");
  if (mesh.rfind("shape:", 0) == 0) {
    scene.mesh = mesh;
  } else {
    std::filesystem::path mesh_path(mesh);
    if (mesh_path.is_relative()) mesh_path = std::filesystem::path(path).parent_path() / mesh_path;
    mesh_path = mesh_path.lexically_normal();
    if (!std::filesystem::exists(mesh_path))
      throw InputError(path + ": key 'mesh' = \"" + mesh + "\": file not found (looked for " + mesh_path.string() +
                       ")");
    scene.mesh = mesh_path.string();
  }

  scene.scale_to_area = read.number("scale_to_area");
  scene.max_circumradius = read.number("max_circumradius");
  scene.min_angle_deg = read.number("min_angle").value_or(0.0);

  // With "species" the top-level count may be left out: it is then the species' sum.
  if (!reaction_diffusion) scene.species = read_species(j, path);
  if (reaction_diffusion) {
    scene.agents = 0;
  } else if (!j.contains("agents") && !scene.species.given()) {
    throw InputError(path + ": required key 'agents' is missing");
  } else if (scene.species.given() && !j.contains("agents")) {
    long long total = 0;
    for (const SpeciesSpec& species : scene.species.species) total += species.agents;
    if (total > static_cast<long long>(std::numeric_limits<int>::max()))
      fail_key(path, "species", "the species' agents add up to " + std::to_string(total) + ", more than " +
                                    std::to_string(std::numeric_limits<int>::max()));
    scene.agents = static_cast<int>(total);
  } else {
    scene.agents = static_cast<int>(*read.integer("agents"));
  }
  scene.time_step = *read.number("time_step");
  const std::string folder = std::filesystem::path(path).parent_path().string();
  if (auto it = j.find("maps"); it != j.end()) {
    scene.maps = parse_maps(*it, folder, path);
    scene.maps_given = *it;
  }
  for (const ParameterSpec& p : kParameterTable) {
    if (reaction_diffusion) break;  // no agent model
    if (auto map = read_parameter_map(j, p, path, p.key)) {
      scene.parameter_maps[static_cast<size_t>(p.id)] = *map;
      scene.parameters[p.id] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    // Absent: the default (optional keys only); null: +infinity (keys that allow it).
    const std::optional<double> file_value = read.number(p.key);
    const double value = file_value ? *file_value : p.default_value.value_or(kInfinity);
    scene.parameters[p.id] = value * p.file_to_si;
  }

  if (auto integrator = read.string("integrator"); integrator && reaction_diffusion) {
    if (*integrator == "forward") scene.reaction_diffusion->integrator = Integrator::Forward;
    else if (*integrator == "imex") scene.reaction_diffusion->integrator = Integrator::Imex;
    else
      throw InputError(path + ": key 'integrator' = \"" + *integrator +
                       "\" is out of range (a reaction-diffusion model takes \"forward\" (explicit, automatic "
                       "sub-steps) or \"imex\" (implicit diffusion, explicit reaction))");
  } else if (integrator) {
    if (*integrator == "forward") scene.integrator = Integrator::Forward;
    else if (*integrator == "backward") scene.integrator = Integrator::Backward;
    else
      throw InputError(path + ": key 'integrator' = \"" + *integrator +
                       "\" is out of range (must be \"forward\" or \"backward\")");
  }
  if (auto seed = read.integer("seed")) scene.seed = static_cast<std::uint32_t>(*seed);
  scene.steps = read.integer("steps");
  scene.sim_time = read.number("sim_time");

  if (auto it = j.find("colormap"); it != j.end() && !it->is_null())
    scene.color_map = resolve_color_map(*it, std::filesystem::path(path).parent_path().string(), path + ": key 'colormap'");

  if (!reaction_diffusion) scene.controls = read_controls(j, path);

  ComparisonSettings& c = scene.comparison;
  c.burn_in = read.number("compare_burn_in").value_or(c.burn_in);
  c.duration = read.number("compare_duration").value_or(c.duration);
  c.sample_interval = read.number("compare_sample_interval").value_or(c.sample_interval);
  c.max_seeds = static_cast<int>(read.integer("compare_seeds").value_or(c.max_seeds));
  c.margin_mean = read.number("compare_margin_mean").value_or(c.margin_mean);
  c.margin_coverage = read.number("compare_margin_coverage").value_or(c.margin_coverage);
  c.margin_spectrum = read.number("compare_margin_spectrum").value_or(c.margin_spectrum);
  c.margin_density = read.number("compare_margin_density").value_or(c.margin_density);
  c.margin_detail = read.number("compare_margin_detail").value_or(c.margin_detail);
  c.spectrum_bands = static_cast<int>(read.integer("compare_bands").value_or(c.spectrum_bands));
  c.eigenpairs = static_cast<int>(read.integer("compare_eigenpairs").value_or(c.eigenpairs));
  if (reaction_diffusion) {
    // A reaction-diffusion scene's run is its own time scale: by default the comparison discards the
    // first half of the run (the pattern forming from its initial state) and averages the second
    // half, sampled 20 times (enough samples that the time average is smooth, few enough that the
    // snapshots' spectra cost little beside the run). Keys given in the file win.
    std::optional<double> run_time = scene.sim_time;
    if (!run_time && scene.steps) run_time = static_cast<double>(*scene.steps) * scene.time_step;
    const bool burn_in_given = j.contains("compare_burn_in"), duration_given = j.contains("compare_duration");
    if (run_time) {
      if (!burn_in_given) c.burn_in = duration_given ? std::max(0.0, *run_time - c.duration) : 0.5 * *run_time;
      if (!duration_given) c.duration = std::max(scene.time_step, *run_time - c.burn_in);
    }
    if (!run_time && !(burn_in_given && duration_given)) {
      // No run length at all: the agent model's defaults are seconds of ITS dynamics and mean
      // nothing for a reaction's, so there is nothing to compare over (physarum compare says so;
      // physarum run takes --steps).
      c.burn_in = 0.0;
      c.duration = 0.0;
    }
    if (!j.contains("compare_sample_interval")) c.sample_interval = std::max(scene.time_step, c.duration / 20.0);
  }
  if (c.sample_interval > c.duration && !(reaction_diffusion && c.duration == 0.0))
    throw InputError(path + ": key 'compare_sample_interval' = " + std::to_string(c.sample_interval) +
                     " is longer than 'compare_duration' = " + std::to_string(c.duration) + " (no sample would be taken)");

  validate_scene(scene);
  return scene;
}

void validate_scene(const Scene& scene) {
  const std::string& s = scene.source;
  if (scene.mesh.empty()) throw InputError(scene_where(s) + ": key 'mesh' is empty (give a file path or shape:NAME)");
  if (scene.scale_to_area) check_range(s, "scale_to_area", *scene.scale_to_area);
  if (scene.max_circumradius) check_range(s, "max_circumradius", *scene.max_circumradius);
  check_range(s, "min_angle", scene.min_angle_deg);
  check_range(s, "time_step", scene.time_step);
  if (scene.steps) check_range(s, "steps", static_cast<double>(*scene.steps));
  if (scene.sim_time) check_range(s, "sim_time", *scene.sim_time);
  if (scene.steps && scene.sim_time)
    throw InputError(scene_where(s) + ": keys 'steps' and 'sim_time' are both given (give at most one run length)");
  if (scene.reaction_diffusion) {
    validate_reaction_diffusion(*scene.reaction_diffusion, scene.maps, s);
    return;
  }
  check_range(s, "agents", scene.agents);
  for (const ParameterSpec& p : kParameterTable) {
    if (const auto& map = scene.parameter_maps[static_cast<size_t>(p.id)]) {
      // The message shows the value, as a number's would: a typo'd number written as text reads as
      // a map name, and the user sees both.
      check_map_reference(scene, std::string(p.key), map->map, MapKind::Scalar, json(map->map).dump());
      continue;  // its values are checked per vertex when the map is evaluated
    }
    const double value = scene.parameters[p.id];
    if (p.null_means_infinite && value == kInfinity) continue;
    check_range(s, p.key, value / p.file_to_si);
  }
  validate_controls(scene);
  validate_species(scene);
}

bool has_parameter_maps(const Scene& scene) {
  return std::any_of(scene.parameter_maps.begin(), scene.parameter_maps.end(), [](const auto& m) { return m.has_value(); });
}

bool steady_mean_is_U(const Scene& scene) {
  for (const Param p : {Param::deposit_rate, Param::decay_rate, Param::mean_lifetime, Param::activation_time})
    if (scene.parameter_maps[static_cast<size_t>(p)]) return false;
  // With species, U holds per layer for each species' own count and rates (common/model/species.hpp), not for
  // the scene's total.
  return !scene.species.given() && scene.controls.write_stimuli.empty() &&
         scene.controls.boundary == BoundaryBehaviour::Reflect;
}

}  // namespace physarum
