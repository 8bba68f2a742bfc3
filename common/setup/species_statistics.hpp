#pragma once
// What the outputs report per species (common/model/species.hpp) beside the existing single-field
// summaries: each species' uniform steady state U_i (Eq. 5 with its own agent count and rates: its
// agents deposit only into its own layer, which decays at its own rate) and, per layer, the mean
// and coverage as stats.csv columns and run.json entries. One species adds nothing: its outputs stay
// those of the base model, byte for byte.
#include "common/setup/agent_inputs.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/scene/scene.hpp"
#include "common/model/species.hpp"
#include "common/surface/surface_domain.hpp"

#include <string>
#include <vector>

namespace physarum {

// U_i per species: Eq. 5 with species i's agents and its parameters' area means (a map summarised
// by its mean, as with_mean_parameters does for the top level, common/setup/scene_maps.hpp).
std::vector<double> species_steady_states(const Scene& scene, const SpeciesSet& species, const SurfaceDomain& domain);

// The stats.csv columns appended for K species, each starting with a comma: ",mean_0,U_0,mean_1,U_1,..."
// (mean_i: layer i's area-weighted mean; U_i its species' steady state); "" for K <= 1.
std::string species_stats_csv_columns(int species_count);
// The matching values of one row (one FieldStatistics per layer, computed with that species' U).
std::string species_stats_csv_values(const std::vector<FieldStatistics>& per_species);

}  // namespace physarum
