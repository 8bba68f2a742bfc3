#include "common/setup/agent_inputs.hpp"

#include "common/model/discrete_steady_state.hpp"
#include "common/simulation/field_statistics.hpp"

namespace physarum {

SimulationSettings simulation_settings(const Scene& scene) {
  SimulationSettings s;
  s.agents = scene.agent_model().agents;
  s.time_step = scene.time_step;
  s.seed = scene.seed;
  s.integrator = scene.agent_model().integrator;
  return s;
}

VertexParameters constant_parameters(const Scene& scene, const SurfaceDomain& domain) {
  return VertexParameters::constant(scene.agent_model().parameters, domain.vertex_count);
}

double uniform_steady_state(const Scene& scene, double area) {
  const ParameterValues& p = scene.agent_model().parameters;
  return uniform_steady_state(scene.agent_model().agents, p[Param::deposit_rate], p[Param::decay_rate], area,
                              p[Param::activation_time], p[Param::mean_lifetime]);
}

double expected_mean_over_U(const Scene& scene, const VertexParameters& parameters, const SurfaceDomain& domain) {
  const ParameterValues& p = scene.agent_model().parameters;
  int sub_steps = 1;
  if (scene.agent_model().integrator == Integrator::Forward) {
    IntrinsicVertexData<double> diffuse_over_mass(static_cast<size_t>(domain.vertex_count));
    for (int v = 0; v < domain.vertex_count; ++v)
      diffuse_over_mass[v] = parameters[Param::diffuse_rate][v] / domain.vertex_mass[v];
    sub_steps = forward_euler_sub_steps(
        scene.time_step, forward_euler_stable_step(domain.laplacian, diffuse_over_mass, parameters[Param::decay_rate]));
  }
  return decay_discretisation_ratio(scene.agent_model().integrator, p[Param::decay_rate], scene.time_step, sub_steps) *
         activation_discretisation_ratio(scene.time_step, p[Param::activation_time], p[Param::mean_lifetime]);
}

}  // namespace physarum
