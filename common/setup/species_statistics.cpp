#include "common/setup/species_statistics.hpp"

#include <algorithm>
#include <cstdio>

namespace physarum {
namespace {

// The area mean of one parameter (exactly its value where it is one value everywhere).
double area_mean(const IntrinsicVertexData<double>& values, const SurfaceDomain& domain) {
  if (std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); })) return values.front();
  double sum = 0.0, mass = 0.0;
  for (int v = 0; v < domain.vertex_count; ++v) sum += domain.vertex_mass[v] * values[v], mass += domain.vertex_mass[v];
  return mass > 0.0 ? sum / mass : values.front();
}

}  // namespace

std::vector<double> species_steady_states(const Scene& scene, const SpeciesSet& species, const SurfaceDomain& domain) {
  std::vector<double> U;
  for (const Species& s : species.species) {
    Scene own = scene;
    for (const ParameterSpec& p : kParameterTable) own.agent_model().parameters[p.id] = area_mean(s.parameters[p.id], domain);
    own.agent_model().agents = s.agents;
    U.push_back(uniform_steady_state(own, domain.total_area));
  }
  return U;
}

std::string species_stats_csv_columns(int species_count) {
  std::string columns;
  for (int s = 0; species_count > 1 && s < species_count; ++s)
    columns += ",mean_" + std::to_string(s) + ",U_" + std::to_string(s);
  return columns;
}

std::string species_stats_csv_values(const std::vector<FieldStatistics>& per_species) {
  std::string values;
  for (size_t s = 0; per_species.size() > 1 && s < per_species.size(); ++s) {
    char buf[64];
    std::snprintf(buf, sizeof buf, ",%.17g,%.17g", per_species[s].mean, per_species[s].U);
    values += buf;
  }
  return values;
}

}  // namespace physarum
