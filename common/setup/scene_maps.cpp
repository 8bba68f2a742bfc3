#include "common/setup/scene_maps.hpp"

#include "common/base/errors.hpp"
#include "common/scene/scene_fields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace physarum {
namespace {

[[noreturn]] void fail_key(const Scene& scene, const std::string& key, const std::string& problem) {
  physarum::fail_key(scene.source, key, problem);
}

IntrinsicVertexData<double> operand_values(const MapOperand& operand, const EvaluatedMaps& maps, int n) {
  if (const auto* value = std::get_if<double>(&operand)) return IntrinsicVertexData<double>(static_cast<size_t>(n), *value);
  return maps.scalar_map(std::get<std::string>(operand));
}

// sum_k coefficient_k * map_k, or empty when there is no term (the backends' "none").
template <class Spec, class Coefficient>
IntrinsicVertexData<double> weighted_sum(const std::vector<Spec>& terms, Coefficient coefficient, const EvaluatedMaps& maps, int n) {
  if (terms.empty()) return {};
  IntrinsicVertexData<double> sum(static_cast<size_t>(n), 0.0);
  for (const Spec& term : terms) {
    const IntrinsicVertexData<double>& values = maps.scalar_map(term.map);
    for (int v = 0; v < n; ++v) sum[v] += coefficient(term) * values[v];
  }
  return sum;
}

}  // namespace

namespace {

// A parameter given by a map, evaluated into `out` (SI units) and checked vertex by vertex; `key`
// names it in messages (p.key, or "species[i].KEY").
void fill_from_map(const Scene& scene, const ParameterSpec& p, const std::string& key, const ParameterMap& map,
                   const EvaluatedMaps& maps, IntrinsicVertexData<double>& out) {
  const IntrinsicVertexData<double>& values = maps.scalar_map(map.map);
  for (size_t v = 0; v < out.size(); ++v) {
    const double file_value = map.range ? (*map.range)[0] + ((*map.range)[1] - (*map.range)[0]) * values[v] : values[v];
    if (!map_value_range(p).contains(file_value))
      fail_key(scene, key,
               "map '" + map.map + "' gives " + ValueRange::number(file_value) + " " + std::string(p.unit) +
                   " at intrinsic vertex " + std::to_string(v) + ", out of range (" + map_value_range(p).describe() + ")" +
                   (map.range ? std::string(" (the map's value there is ") + ValueRange::number(values[v]) +
                                    "; a range remaps values 0..1)"
                              : std::string()));
    out[v] = file_value * p.file_to_si;
  }
}

}  // namespace

VertexParameters vertex_parameters(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps) {
  const int n = surface.domain.vertex_count;
  VertexParameters parameters = VertexParameters::constant(scene.agent_model().parameters, n);
  for (const ParameterSpec& p : kParameterTable)
    if (const auto& map = scene.agent_model().parameter_maps[static_cast<size_t>(p.id)])
      fill_from_map(scene, p, std::string(p.key), *map, maps, parameters[p.id]);
  return parameters;
}

SpeciesSet species_set(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps,
                       const VertexParameters& parameters) {
  const SceneSpecies& given = scene.agent_model().species;
  if (!given.given()) return SpeciesSet::single(scene.agent_model().agents, parameters);
  const int n = surface.domain.vertex_count;
  SpeciesSet set;
  for (size_t i = 0; i < given.species.size(); ++i) {
    const SpeciesSpec& spec = given.species[i];
    Species species{spec.agents, parameters};
    for (const ParameterSpec& p : kParameterTable) {
      const size_t index = static_cast<size_t>(p.id);
      if (const auto& map = spec.parameter_maps[index])
        fill_from_map(scene, p, "species[" + std::to_string(i) + "]." + std::string(p.key), *map, maps, species.parameters[p.id]);
      else if (const auto& value = spec.parameters[index])
        species.parameters[p.id] = IntrinsicVertexData<double>(static_cast<size_t>(n), *value);
    }
    set.species.push_back(std::move(species));
  }
  const size_t k = set.species.size();
  if (given.sensing.empty()) {
    set.sensing.assign(k * k, 0.0);
    for (size_t i = 0; i < k; ++i) set.sensing[i * k + i] = 1.0;
  } else {
    set.sensing = given.sensing;
  }
  return set;
}

SimulationControls simulation_controls(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps) {
  const int n = surface.domain.vertex_count;
  const SceneControls& c = scene.agent_model().controls;
  SimulationControls controls;
  controls.read_stimulus = weighted_sum(c.read_stimuli, [](const ReadStimulusSpec& s) { return s.weight; }, maps, n);
  controls.write_rate = weighted_sum(c.write_stimuli, [](const WriteStimulusSpec& s) { return s.rate; }, maps, n);
  // A constant weight is the base model's uniform spawning (validate_scene refused 0 and below).
  if (c.spawn_weight && std::holds_alternative<std::string>(*c.spawn_weight)) {
    const std::string& name = std::get<std::string>(*c.spawn_weight);
    controls.spawn_weight = maps.scalar_map(name);
    bool any_positive = false;
    for (int v = 0; v < n; ++v) {
      if (!(controls.spawn_weight[v] >= 0.0))
        fail_key(scene, "spawn_weight", "map '" + name + "' gives " + ValueRange::number(controls.spawn_weight[v]) +
                                            " at intrinsic vertex " + std::to_string(v) + " (spawn weights must be >= 0)");
      any_positive = any_positive || controls.spawn_weight[v] > 0.0;
    }
    if (!any_positive)
      fail_key(scene, "spawn_weight", "map '" + name + "' is zero everywhere: no agent could be placed (all spawn weights are zero)");
  }
  if (c.bias) {
    DirectionalBias bias;
    bias.direction = maps.vector_map(c.bias->direction);
    bias.strength = operand_values(c.bias->strength, maps, n);
    for (int v = 0; v < n; ++v) {
      if (!(bias.strength[v] >= 0.0))
        fail_key(scene, "bias", "\"strength\" gives " + ValueRange::number(bias.strength[v]) + " deg/s at intrinsic vertex " +
                                    std::to_string(v) + " (must be >= 0)");
      bias.strength[v] *= kDegree;  // the file's deg/s -> rad/s
    }
    bias.symmetry = c.bias->symmetry;
    controls.bias = std::move(bias);
  }
  controls.spawn_heading = c.spawn_heading;
  controls.boundary = c.boundary;
  return controls;
}

VertexParameters vertex_parameters(const Scene& scene, const PreparedSurface& surface) {
  return vertex_parameters(scene, surface, evaluate_maps(scene.maps, surface, scene_where(scene.source)));
}

SimulationControls simulation_controls(const Scene& scene, const PreparedSurface& surface) {
  return simulation_controls(scene, surface, evaluate_maps(scene.maps, surface, scene_where(scene.source)));
}

SceneArrays scene_arrays(const Scene& scene, const PreparedSurface& surface) {
  return scene_arrays(scene, surface, evaluate_maps(scene.maps, surface, scene_where(scene.source)));
}

SceneArrays scene_arrays(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps) {
  VertexParameters parameters = vertex_parameters(scene, surface, maps);
  SpeciesSet species = species_set(scene, surface, maps, parameters);
  return SceneArrays{std::move(parameters), simulation_controls(scene, surface, maps), std::move(species)};
}

Scene with_mean_parameters(Scene scene, const VertexParameters& parameters, const SurfaceDomain& domain) {
  const double total_mass = std::accumulate(domain.vertex_mass.begin(), domain.vertex_mass.end(), 0.0);
  for (const ParameterSpec& p : kParameterTable) {
    if (!scene.agent_model().parameter_maps[static_cast<size_t>(p.id)]) continue;
    const IntrinsicVertexData<double>& values = parameters[p.id];
    double sum = 0.0;
    for (int v = 0; v < domain.vertex_count; ++v) sum += domain.vertex_mass[v] * values[v];
    scene.agent_model().parameters[p.id] = total_mass > 0.0 ? sum / total_mass : values.front();
  }
  return scene;
}

}  // namespace physarum
