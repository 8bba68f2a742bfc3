#include "common/scene/scene_json.hpp"

#include <cmath>

namespace physarum {

nlohmann::ordered_json model_json(const AgentModelSpec&, const Scene& scene) { return scene_parameters_json(scene); }

nlohmann::ordered_json scene_parameters_json(const Scene& s) {
  const AgentModelSpec& a = s.agent_model();
  nlohmann::ordered_json j;
  j["mesh"] = s.mesh;
  j["scale_to_area"] = s.scale_to_area ? nlohmann::ordered_json(*s.scale_to_area) : nlohmann::ordered_json();
  j["max_circumradius"] = s.max_circumradius ? nlohmann::ordered_json(*s.max_circumradius) : nlohmann::ordered_json();
  j["min_angle"] = s.min_angle_deg;
  j["agents"] = a.agents;
  j["time_step"] = s.time_step;
  for (const ParameterSpec& p : kParameterTable) {
    const double value = a.parameters[p.id];
    if (const auto& map = a.parameter_maps[static_cast<size_t>(p.id)]) {
      nlohmann::ordered_json m;
      m["map"] = map->map;
      if (map->range) m["range"] = {(*map->range)[0], (*map->range)[1]};
      if (std::isfinite(value)) m["mean"] = to_file_units(p, value);
      j[std::string(p.key)] = m;
      continue;
    }
    j[std::string(p.key)] = p.null_means_infinite && std::isinf(value) ? nlohmann::ordered_json()
                                                                        : nlohmann::ordered_json(to_file_units(p, value));
  }
  j["integrator"] = integrator_name(a.integrator);
  j["seed"] = s.seed;
  if (!s.maps.empty()) j["maps"] = s.maps_given;
  const SceneControls& c = a.controls;
  auto operand = [](const MapOperand& o) {
    return std::holds_alternative<double>(o) ? nlohmann::ordered_json(std::get<double>(o))
                                             : nlohmann::ordered_json(std::get<std::string>(o));
  };
  for (const ReadStimulusSpec& r : c.read_stimuli) j["read_stimuli"].push_back({{"map", r.map}, {"weight", r.weight}});
  for (const WriteStimulusSpec& w : c.write_stimuli) j["write_stimuli"].push_back({{"map", w.map}, {"rate", w.rate}});
  if (c.spawn_weight) j["spawn_weight"] = operand(*c.spawn_weight);
  if (c.bias) {
    nlohmann::ordered_json b;
    b["direction"] = c.bias->direction;
    b["strength"] = operand(c.bias->strength);
    b["symmetry"] = c.bias->symmetry;
    j["bias"] = b;
  }
  if (c.spawn_heading != SpawnHeading::Random) j["spawn_heading"] = "bias";
  if (c.boundary != BoundaryBehaviour::Reflect) j["boundary"] = "terminate";
  // Competing species: each entry's agents and overrides as the file gave them (file units).
  for (const SpeciesSpec& species : a.species.species) {
    nlohmann::ordered_json entry;
    entry["agents"] = species.agents;
    for (const ParameterSpec& p : kParameterTable) {
      const size_t index = static_cast<size_t>(p.id);
      if (const auto& map = species.parameter_maps[index]) {
        nlohmann::ordered_json m;
        m["map"] = map->map;
        if (map->range) m["range"] = {(*map->range)[0], (*map->range)[1]};
        entry[std::string(p.key)] = m;
      } else if (const auto& value = species.parameters[index]) {
        entry[std::string(p.key)] = p.null_means_infinite && std::isinf(*value) ? nlohmann::ordered_json()
                                                                               : nlohmann::ordered_json(to_file_units(p, *value));
      }
    }
    j["species"].push_back(entry);
  }
  if (!a.species.sensing.empty()) {
    const size_t k = a.species.species.size();
    for (size_t row = 0; row < k; ++row)
      j["sensing"].push_back(std::vector<double>(a.species.sensing.begin() + static_cast<long>(row * k),
                                                 a.species.sensing.begin() + static_cast<long>((row + 1) * k)));
  }
  return j;
}

}  // namespace physarum
