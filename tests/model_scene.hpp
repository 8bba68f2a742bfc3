#pragma once
// The model parameters the simulation tests share (the default scene's, with a faster decay so a
// test reaches steady state in a few simulated seconds): one description for the reference tests,
// the OpenCL tests and the device check, so they test the same model.
#include "common/scene/default_scene.hpp"

#include <limits>
#include <optional>

namespace physarum::testing {

inline Scene model_scene(int agents, double time_step, std::optional<double> mean_lifetime, Integrator integrator) {
  Scene s = default_scene_parameters(agents);
  s.time_step = time_step;
  s.agent_model().parameters[Param::decay_rate] = 2.5;
  s.agent_model().parameters[Param::mean_lifetime] = mean_lifetime.value_or(std::numeric_limits<double>::infinity());
  s.agent_model().parameters[Param::activation_time] = 0.1;
  s.agent_model().integrator = integrator;
  s.seed = 11;
  return s;
}

}  // namespace physarum::testing
