#include "common/model/simulation_controls.hpp"

#include "common/model/directional_bias.hpp"
#include "common/base/errors.hpp"
#include "common/surface/surface_domain.hpp"

#include <cmath>

namespace physarum {

namespace {

void check_vertex_control(const IntrinsicVertexData<double>& values, int vertex_count, bool non_negative,
                          const std::string& who, const char* what) {
  if (values.empty()) return;
  if (values.size() != static_cast<size_t>(vertex_count))
    throw InputError(who + ": " + what + " has " + std::to_string(values.size()) + " values for " +
                     std::to_string(vertex_count) + " vertices");
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]) || (non_negative && values[i] < 0.0))
      throw InputError(who + ": " + what + " at vertex " + std::to_string(i) + " is " + std::to_string(values[i]) +
                       (non_negative ? " (must be finite and >= 0)" : " (must be finite)"));
}

}  // namespace

void check_controls(const SurfaceDomain& domain, const SimulationControls& controls, const std::string& who) {
  check_vertex_control(controls.read_stimulus, domain.vertex_count, false, who, "read_stimulus");
  check_vertex_control(controls.write_rate, domain.vertex_count, false, who, "write_rate");
  check_vertex_control(controls.spawn_weight, domain.vertex_count, true, who, "spawn_weight");
  if (controls.bias) {
    try {
      check_directional_bias(domain, *controls.bias);
    } catch (const InputError& e) {
      throw InputError(who + ": " + e.what());
    }
  }
}

}  // namespace physarum
