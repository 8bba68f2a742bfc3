#pragma once
// The model parameters of the built-in default scene (tools/scenes/default.json: Table 1 of the
// paper on a 4 m^2 surface), for code that builds a scene without a file: the benchmarks and the
// tests. No surface fields: such code brings its own domain. A test keeps this equal to the file.
#include "common/scene/scene.hpp"

#include <numbers>

namespace physarum {

inline Scene default_scene_parameters(int agents) {
  Scene s;
  AgentModelSpec& a = s.agent_model();
  a.agents = agents;
  s.time_step = 0.01;
  a.parameters[Param::sensor_distance] = 0.05;
  a.parameters[Param::sensor_angle] = 22.5 * kDegree;
  a.parameters[Param::move_rate] = 0.5;
  a.parameters[Param::turn_rate] = 180.0 * kDegree;
  a.parameters[Param::turn_frequency] = 20.0;
  a.parameters[Param::deposit_rate] = 1.0;
  a.parameters[Param::decay_rate] = 1.0;
  a.parameters[Param::diffuse_rate] = 0.0002;
  a.parameters[Param::mean_lifetime] = 1.0;
  a.parameters[Param::activation_time] = 0.2;
  a.integrator = Integrator::Forward;
  s.seed = 1;
  return s;
}

}  // namespace physarum
