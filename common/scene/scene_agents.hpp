#pragma once
// The agent model's part of a scene (paper 000 Table 1, Sec. 3.3; paper 001's species): the agent
// count, every model parameter as a number or a map, the controls, the species and the pheromone
// integrator. Read by read_agent_model from the scene's keys; common/setup/ evaluates it on a
// surface into the backends' inputs.
#include "common/maps/map_definition.hpp"
#include "common/scene/model_tag.hpp"
#include "common/model/diffusion_decay.hpp"
#include "common/model/model_parameters.hpp"
#include "common/scene/scene_controls.hpp"
#include "common/scene/scene_parameters.hpp"
#include "common/scene/scene_species.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

struct AgentModelSpec {
  int agents = 0;  // N (with "species": the sum of the species' agents)
  // Every model parameter of Table 1 (common/model/model_parameters.hpp), in SI units. A parameter given
  // by a map (parameter_maps[p] set) holds NaN here until the surface exists: its values are per
  // vertex (common/setup/scene_maps.hpp: vertex_parameters, and with_mean_parameters for one summary value).
  ParameterValues parameters;
  std::array<std::optional<ParameterMap>, kParamCount> parameter_maps;
  SceneControls controls;     // paper Sec. 3.3
  SceneSpecies species;       // "species" and "sensing" (competing species); empty: one population
  Integrator integrator = Integrator::Forward;  // for the pheromone PDE (Eq. 6 / 7)
};

// The keys of the agent model alone: its count, its parameters (Table 1), the controls and species
// (a reaction–diffusion scene refuses them).
std::vector<std::string> agent_model_keys();

// Reads the agent model's keys of a scene object ("integrator" included). InputError naming the key.
AgentModelSpec read_agent_model(const nlohmann::json& scene, const std::string& source);

// The values in range, every map a parameter, control or species names in `maps` with the kind
// needed, the species adding up to the agent count.
void validate_agent_model(const AgentModelSpec& model, const MapSet& maps, const std::string& source);

// The scene layer's names for the above (common/scene/scene_models.hpp). The agent model is the
// default: it reads any scene no other model claimed.
struct Scene;
inline std::optional<AgentModelSpec> read_model(ModelTag<AgentModelSpec>, const nlohmann::json& scene,
                                                const std::string& source) {
  return read_agent_model(scene, source);
}
inline std::string model_key(const AgentModelSpec&) { return "physarum"; }
// The harness's default run length is seconds of the agents' own dynamics (ComparisonSettings).
inline bool compares_over_its_run_length(const AgentModelSpec&) { return false; }
inline void validate_model(const AgentModelSpec& model, const MapSet& maps, const std::string& source) {
  validate_agent_model(model, maps, source);
}
nlohmann::ordered_json model_json(const AgentModelSpec& model, const Scene& scene);  // scene_parameters_json

// True when some model parameter is given by a map.
bool has_parameter_maps(const AgentModelSpec& model);

// True when the pheromone's steady mean is U (Eq. 5) for this model: U counts the deposits of N
// agents at a uniform deposit rate and active fraction against a uniform decay, so it holds with any
// maps on the other parameters, read-stimuli, spawn weights and a bias, but not with a mapped
// deposit_rate, decay_rate, mean_lifetime (sinks included) or activation_time, with write-stimuli
// (pheromone not from agents), with a terminating boundary (lifetimes cut short), or with species
// (each layer's mean is its own species' U instead).
bool steady_mean_is_U(const AgentModelSpec& model);

}  // namespace physarum
