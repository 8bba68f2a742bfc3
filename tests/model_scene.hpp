#pragma once
// The model parameters the simulation tests share (the default scene's, with a faster decay so a
// test reaches steady state in a few simulated seconds): one description for the reference tests,
// the OpenCL tests and the device check, so they test the same model.
#include "common/scene.hpp"

#include <numbers>
#include <optional>

namespace physarum::testing {

inline Scene model_scene(int agents, double time_step, std::optional<double> mean_lifetime, Integrator integrator) {
  constexpr double kDegree = std::numbers::pi / 180.0;
  Scene s;
  s.agents = agents;
  s.time_step = time_step;
  s.sensor_distance = 0.05;
  s.sensor_angle = 22.5 * kDegree;
  s.move_rate = 0.5;
  s.turn_rate = 180.0 * kDegree;
  s.turn_frequency = 20.0;
  s.deposit_rate = 1.0;
  s.decay_rate = 2.5;
  s.diffuse_rate = 0.0002;
  s.mean_lifetime = mean_lifetime;
  s.activation_time = 0.1;
  s.integrator = integrator;
  s.seed = 11;
  return s;
}

}  // namespace physarum::testing
