#pragma once
// The one vocabulary of time integrators, shared by every model (the scene key "integrator" spells
// them "forward", "backward" and "imex"); each model takes the ones that fit it:
//   Forward   forward Euler, in sub-steps below the stability limit (agents' pheromone, reaction-diffusion)
//   Backward  backward Euler, one implicit solve per step (agents' pheromone, Eq. 7)
//   Imex      implicit diffusion, explicit reaction (reaction-diffusion)
namespace physarum {

enum class Integrator { Forward, Backward, Imex };

// The scene key's spelling: "forward", "backward", "imex".
inline const char* integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::Forward: return "forward";
    case Integrator::Backward: return "backward";
    case Integrator::Imex: return "imex";
  }
  return "forward";
}

}  // namespace physarum
