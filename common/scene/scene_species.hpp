#pragma once
// Competing species (MoMaS, paper 001 Sec. 2.5) as a scene file states them: "species", a list of
// agent populations, each with its own pheromone layer, and "sensing", the K x K interaction matrix
// (row i = what species i's sensors read: sum_j m_ij * layer_j). Each entry overrides any Table-1
// parameter with a number or a map, exactly like the top-level keys; what it does not override it
// inherits from the top level. Evaluated on a surface these become common/model/species.hpp's SpeciesSet.
//
// A scene without "species" has none here and runs the single-species base model, bit for bit.
#include "common/model/model_parameters.hpp"
#include "common/maps/map_definition.hpp"
#include "common/scene/scene_parameters.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <vector>

namespace physarum {

struct SpeciesSpec {
  int agents = 0;  // "agents": this population's size (>= 1)
  // Overrides, per Table-1 parameter (table order): a number in SI units (+infinity for a null
  // mean_lifetime), or a map; neither set = the top-level value (number or map).
  std::array<std::optional<double>, kParamCount> parameters;
  std::array<std::optional<ParameterMap>, kParamCount> parameter_maps;
};

struct SceneSpecies {
  std::vector<SpeciesSpec> species;  // empty: no "species" (one population, the base model)
  // Row-major K x K, finite; empty with species given: the identity (each reads its own layer only).
  std::vector<double> sensing;

  bool given() const { return !species.empty(); }
};

// Reads "species" and "sensing" (both absent: no species). The entries' parameter values are
// checked like the top-level keys' (validate_species), with messages naming "species[i].KEY".
SceneSpecies read_species(const nlohmann::json& scene, const std::string& source);

// Every species' overrides in their parameter's range (numbers) or naming a scalar map of `maps`,
// its agent count allowed and adding up to `agents` (the scene's total), and the sensing matrix
// K x K and finite.
void validate_species(const SceneSpecies& species, int agents, const MapSet& maps, const std::string& source);

}  // namespace physarum
