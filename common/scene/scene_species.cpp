#include "common/scene/scene_species.hpp"

#include "common/scene/scene_fields.hpp"
#include "common/scene/scene_keys.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

namespace physarum {

using nlohmann::json;

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

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
      if (!find_scene_key("agents")->range.contains(agents->get<double>()))
        fail_key(source, agents_key, agents->dump() + " is out of range (" + find_scene_key("agents")->range.describe() + ")");
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
          fail_key(source, "sensing", std::string("[") + std::to_string(row) + "][" + std::to_string(col) + "] = " + r[col].dump() +
                                          " must be a number");
        result.sensing.push_back(r[col].get<double>());
      }
    }
  }
  return result;
}

void validate_species(const SceneSpecies& sp, int agents, const MapSet& maps, const std::string& source) {
  if (!sp.given()) {
    if (!sp.sensing.empty()) fail_key(source, "sensing", "an interaction matrix between species, and the scene has no 'species'");
    return;
  }
  long long total = 0;
  for (size_t i = 0; i < sp.species.size(); ++i) {
    const SpeciesSpec& species = sp.species[i];
    const std::string name = entry_name("species", i);
    check_range(source, "agents", species.agents);  // the same range as the top-level count
    total += species.agents;
    for (const ParameterSpec& p : kParameterTable) {
      const std::string key = name + "." + std::string(p.key);
      const size_t index = static_cast<size_t>(p.id);
      if (const auto& map = species.parameter_maps[index]) {
        check_map_reference(maps, source, key, map->map, MapKind::Scalar, json(map->map).dump());
        continue;
      }
      if (!species.parameters[index]) continue;
      const double value = *species.parameters[index];
      if (p.null_means_infinite && value == kInfinity) continue;
      const double file_value = value / p.file_to_si;
      if (!p.range.contains(file_value)) fail_range(source, key, ValueRange::number(file_value), p.range);
    }
  }
  if (total != agents)
    fail_key(source, "agents", std::to_string(agents) + " differs from the sum of the species' agents (" +
                                         std::to_string(total) + "); leave it out, or give the sum");
  const size_t k = sp.species.size();
  if (!sp.sensing.empty() && sp.sensing.size() != k * k)
    fail_key(source, "sensing", "has " + std::to_string(sp.sensing.size()) + " entries; a " + std::to_string(k) +
                                          " x " + std::to_string(k) + " matrix has " + std::to_string(k * k));
  for (size_t e = 0; e < sp.sensing.size(); ++e)
    if (!std::isfinite(sp.sensing[e]))
      fail_key(source, "sensing", "[" + std::to_string(e / k) + "][" + std::to_string(e % k) + "] = " +
                                            ValueRange::number(sp.sensing[e]) + " must be finite");
}

}  // namespace physarum
