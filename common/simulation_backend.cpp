#include "common/simulation_backend.hpp"

namespace physarum {

SimulationSettings simulation_settings(const Scene& scene) {
  SimulationSettings s;
  s.agents = scene.agents;
  s.time_step = scene.time_step;
  s.seed = scene.seed;
  s.integrator = scene.integrator;
  return s;
}

}  // namespace physarum
