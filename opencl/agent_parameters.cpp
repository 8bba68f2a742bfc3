#include "opencl/agent_parameters.hpp"

#include "reference/turnover.hpp"

namespace physarum::opencl {
namespace {

static_assert(sizeof(PhysarumAgentParameters) == 32, "PhysarumAgentParameters: eight floats");

PhysarumAgentParameters parameters_of_vertex(const VertexParameters& p, const std::vector<double>& hazard, size_t i) {
  PhysarumAgentParameters r;
  r.sensor_distance = static_cast<float>(p.sensor_distance[i]);
  r.sensor_angle = static_cast<float>(p.sensor_angle[i]);
  r.move_rate = static_cast<float>(p.move_rate[i]);
  r.turn_rate = static_cast<float>(p.turn_rate[i]);
  r.turn_frequency = static_cast<float>(p.turn_frequency[i]);
  r.deposit_rate = static_cast<float>(p.deposit_rate[i]);
  r.hazard_rate = static_cast<float>(hazard[i]);
  r.activation_time = static_cast<float>(p.activation_time[i]);
  return r;
}

}  // namespace

PackedAgentParameters pack_agent_parameters(const VertexParameters& params) {
  const std::vector<double> hazard = hazard_rate_per_vertex(params.mean_lifetime);
  PackedAgentParameters packed;
  packed.per_vertex.resize(params.sensor_distance.size());
  for (size_t i = 0; i < packed.per_vertex.size(); ++i) packed.per_vertex[i] = parameters_of_vertex(params, hazard, i);
  for (const std::vector<double>* field : {&params.sensor_distance, &params.sensor_angle, &params.move_rate,
                                           &params.turn_rate, &params.turn_frequency, &params.deposit_rate,
                                           &params.mean_lifetime, &params.activation_time})
    packed.uniform = packed.uniform && is_uniform(*field);
  return packed;
}

}  // namespace physarum::opencl
