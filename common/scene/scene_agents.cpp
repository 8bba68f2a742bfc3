#include "common/scene/scene_agents.hpp"

#include "common/base/errors.hpp"
#include "common/scene/scene_fields.hpp"
#include "common/scene/scene_keys.hpp"

#include <algorithm>
#include <limits>

namespace physarum {
namespace {

using nlohmann::json;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// With "species" the top-level count may be left out: it is then the species' sum.
int read_agent_count(const json& j, const SceneSpecies& species, const std::string& source) {
  if (!j.contains("agents") && !species.given()) throw InputError(source + ": required key 'agents' is missing");
  if (species.given() && !j.contains("agents")) {
    long long total = 0;
    for (const SpeciesSpec& s : species.species) total += s.agents;
    if (total > static_cast<long long>(std::numeric_limits<int>::max()))
      fail_key(source, "species", "the species' agents add up to " + std::to_string(total) + ", more than " +
                                      std::to_string(std::numeric_limits<int>::max()));
    return static_cast<int>(total);
  }
  return static_cast<int>(*SceneReader{j, source}.integer("agents"));
}

Integrator read_agent_integrator(const json& j, const std::string& source) {
  const auto integrator = SceneReader{j, source}.string("integrator");
  if (!integrator || *integrator == "forward") return Integrator::Forward;
  if (*integrator == "backward") return Integrator::Backward;
  throw InputError(source + ": key 'integrator' = \"" + *integrator +
                   "\" is out of range (must be \"forward\" or \"backward\")");
}

}  // namespace

std::vector<std::string> agent_model_keys() {
  std::vector<std::string> keys = {"agents", "read_stimuli", "write_stimuli", "spawn_weight", "bias",
                                   "spawn_heading", "boundary", "species", "sensing"};
  for (const ParameterSpec& p : kParameterTable) keys.emplace_back(p.key);
  return keys;
}

AgentModelSpec read_agent_model(const json& j, const std::string& source) {
  const SceneReader read{j, source};
  AgentModelSpec model;
  model.species = read_species(j, source);
  model.agents = read_agent_count(j, model.species, source);
  for (const ParameterSpec& p : kParameterTable) {
    if (auto map = read_parameter_map(j, p, source, p.key)) {
      model.parameter_maps[static_cast<size_t>(p.id)] = *map;
      model.parameters[p.id] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    // Absent: the default (optional keys only); null: +infinity (keys that allow it).
    const std::optional<double> file_value = read.number(p.key);
    const double value = file_value ? *file_value : p.default_value.value_or(kInfinity);
    model.parameters[p.id] = value * p.file_to_si;
  }
  model.integrator = read_agent_integrator(j, source);
  model.controls = read_controls(j, source);
  return model;
}

void validate_agent_model(const AgentModelSpec& model, const MapSet& maps, const std::string& s) {
  check_range(s, "agents", model.agents);
  for (const ParameterSpec& p : kParameterTable) {
    if (const auto& map = model.parameter_maps[static_cast<size_t>(p.id)]) {
      // The message shows the value, as a number's would: a typo'd number written as text reads as
      // a map name, and the user sees both.
      check_map_reference(maps, s, std::string(p.key), map->map, MapKind::Scalar, json(map->map).dump());
      continue;  // its values are checked per vertex when the map is evaluated
    }
    const double value = model.parameters[p.id];
    if (p.null_means_infinite && value == kInfinity) continue;
    check_range(s, p.key, value / p.file_to_si);
  }
  validate_controls(model.controls, maps, s);
  validate_species(model.species, model.agents, maps, s);
}

bool has_parameter_maps(const AgentModelSpec& model) {
  return std::any_of(model.parameter_maps.begin(), model.parameter_maps.end(), [](const auto& m) { return m.has_value(); });
}

bool steady_mean_is_U(const AgentModelSpec& model) {
  for (const Param p : {Param::deposit_rate, Param::decay_rate, Param::mean_lifetime, Param::activation_time})
    if (model.parameter_maps[static_cast<size_t>(p)]) return false;
  // With species, U holds per layer for each species' own count and rates (common/model/species.hpp), not for
  // the scene's total.
  return !model.species.given() && model.controls.write_stimuli.empty() &&
         model.controls.boundary == BoundaryBehaviour::Reflect;
}

}  // namespace physarum
