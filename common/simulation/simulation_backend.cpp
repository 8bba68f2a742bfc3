#include "common/simulation/simulation_backend.hpp"

#include "common/base/errors.hpp"
#include "common/simulation/simulation_state.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/model/vertex_parameters.hpp"

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
  if (settings.integrator == Integrator::Imex)
    throw InputError(who + ": integrator 'imex' is reaction-diffusion's; the pheromone is forward or backward");
  for (size_t i = 0; i < n; ++i)
    if (!(params[Param::turn_frequency][i] > 0.0))
      throw InputError(who + ": turn_frequency at vertex " + std::to_string(i) + " is " +
                       std::to_string(params[Param::turn_frequency][i]) + " (must be > 0)");
}

void check_layer_index(int layer, int layer_count, const std::string& who, const std::string& what) {
  if (layer < 0 || layer >= layer_count)
    throw InputError(who + ": " + what + ": no field layer " + std::to_string(layer) + " (layers 0.." +
                     std::to_string(layer_count - 1) + ")");
}

void check_layer_values(const IntrinsicVertexData<double>& values, int vertex_count, int layer,
                        const std::string& who, const std::string& what) {
  if (values.size() != static_cast<size_t>(vertex_count))
    throw InputError(who + ": " + what + " of field layer " + std::to_string(layer) + " got " +
                     std::to_string(values.size()) + " values for " + std::to_string(vertex_count) + " vertices");
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw InputError(who + ": " + what + " of field layer " + std::to_string(layer) + ": the value at vertex " +
                       std::to_string(i) + " is " + std::to_string(values[i]) + " (must be finite)");
}

void check_layer_value(double value, int layer, const std::string& who, const std::string& what) {
  if (!std::isfinite(value))
    throw InputError(who + ": " + what + " of field layer " + std::to_string(layer) + " with " +
                     std::to_string(value) + " (must be finite)");
}

void check_state_fits(const SimulationState& state, int layer_count, int vertex_count, int agent_count, int face_count,
                      const std::string& who) {
  const std::string what = who + ": restore_state: ";
  if (state.steps_taken < 0) throw InputError(what + "step count " + std::to_string(state.steps_taken) + " is negative");
  if (!std::isfinite(state.time)) throw InputError(what + "the time is not finite");
  if (static_cast<int>(state.layers.size()) != layer_count)
    throw InputError(what + "the state has " + std::to_string(state.layers.size()) + " field layers, this simulation " +
                     std::to_string(layer_count));
  for (int layer = 0; layer < layer_count; ++layer)
    check_layer_values(state.layers[static_cast<size_t>(layer)], vertex_count, layer, who, "restore_state");
  const Agents& a = state.agents;
  const size_t n = static_cast<size_t>(a.count());
  if (a.count() != agent_count)
    throw InputError(what + "the state has " + std::to_string(a.count()) + " agents, this simulation " +
                     std::to_string(agent_count));
  if (a.position.size() != n || a.heading.size() != n || a.age.size() != n || a.exposure.size() != n ||
      a.exposure_threshold.size() != n || a.time_since_decision.size() != n || a.accumulated_turn.size() != n)
    throw InputError(what + "the agents' attribute arrays differ in length");
  for (size_t i = 0; i < n; ++i)
    if (a.face[i] < 0 || a.face[i] >= face_count)
      throw InputError(what + "agent " + std::to_string(i) + " stands on face " + std::to_string(a.face[i]) + " of " +
                       std::to_string(face_count));
}

}  // namespace physarum
