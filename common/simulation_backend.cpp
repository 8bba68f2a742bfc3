#include "common/simulation_backend.hpp"

#include "common/errors.hpp"
#include "common/surface_domain.hpp"
#include "common/vertex_parameters.hpp"

#include <cmath>

namespace physarum {

void check_simulation_inputs(const SurfaceDomain& domain, const VertexParameters& params,
                             const SimulationSettings& settings, const std::string& who) {
  const size_t n = static_cast<size_t>(domain.vertex_count);
  for (const ParameterSpec& p : kParameterTable)
    if (params[p.id].size() != n)
      throw InputError(who + ": the parameter map of '" + std::string(p.key) + "' has " +
                       std::to_string(params[p.id].size()) + " values for " + std::to_string(n) + " vertices");
  if (settings.agents < 0) throw InputError(who + ": agents " + std::to_string(settings.agents) + " must be >= 0");
  if (!(settings.time_step > 0.0) || !std::isfinite(settings.time_step))
    throw InputError(who + ": time_step " + std::to_string(settings.time_step) + " must be > 0");
  for (size_t i = 0; i < n; ++i)
    if (!(params[Param::turn_frequency][i] > 0.0))
      throw InputError(who + ": turn_frequency at vertex " + std::to_string(i) + " is " +
                       std::to_string(params[Param::turn_frequency][i]) + " (must be > 0)");
}

SimulationSettings simulation_settings(const Scene& scene) {
  SimulationSettings s;
  s.agents = scene.agents;
  s.time_step = scene.time_step;
  s.seed = scene.seed;
  s.integrator = scene.integrator;
  return s;
}

}  // namespace physarum
