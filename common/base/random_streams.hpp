#pragma once
// Which random numbers an agent uses, and when (the same in both backends). Every random
// draw of the simulation is one Philox4x32-10 block addressed by
//
//   key     = (seed, agent id)
//   counter = (step, purpose, index, 0)
//
// so (seed, agent, step, purpose) always yields the same numbers, whatever the order in which
// agents are processed, the backend or the device: a run is bit-reproducible and the OpenCL kernels
// can reproduce the reference draw for draw. `step` is the index n of the step being taken (the
// one that advances time from n*dt to (n+1)*dt); the initial state uses step 0 with purposes of its
// own, so it never collides with step 0's draws. `index` numbers the blocks of one purpose when a
// decision needs more than four words. The OpenCL backend reuses this header verbatim (the values
// of RandomPurpose are part of the contract: never renumber them, only append).
#include "common/base/philox.hpp"

#include <cstdint>

namespace physarum {

enum class RandomPurpose : std::uint32_t {
  // Initial state, counter step 0.
  InitialPlacement = 1,  // blocks 0, 1: face choice (2 doubles), position in the face (2 doubles)
  InitialState = 2,      // block 0: heading, elapsed exposure; block 1: remaining exposure, decision phase
  // Per step, counter step n.
  TurnDirection = 3,     // block 0: bit 31 of word k picks left (0) or right (1) for the k-th
                         //          decision due in this step (k < 4)
  RespawnPlacement = 4,  // blocks 0, 1: as InitialPlacement
  RespawnState = 5,      // block 0: heading, exposure threshold
  // Spawn weights only (common/model/spawn_distribution.hpp): the corner a weighted (re)spawn point leans
  // toward, block 0, first uniform. Purposes of their own, so the base model's draws stay as they were.
  InitialSpawnCorner = 6,  // counter step 0
  RespawnCorner = 7,       // counter step n
  // Reaction-diffusion initial states (common/setup/reaction_diffusion_build.hpp), counter step 0; the
  // stream is the intrinsic vertex (noise) or the spot (spot centres), not an agent.
  ReactionNoise = 8,       // block = morphogen: first uniform, the vertex's noise draw
  ReactionSpot = 9,        // block 0: first uniform, the spot centre's place in the mass distribution
  ReactionParameterNoise = 10,  // block = coefficient: first uniform, the vertex's draw ("parameter_noise")
  // The growth model's shell (common/shell/sheet_perturbation.hpp): the stream is the vertex, the counter
  // step the growth step.
  ShellPerturbation = 11,  // block 0: first uniform, the vertex's out-of-plane offset
};

inline PhiloxWords agent_random_words(std::uint32_t seed, std::uint32_t agent, std::uint32_t step, RandomPurpose purpose,
                                      std::uint32_t index = 0) {
  return random_words(seed, agent, step, static_cast<std::uint32_t>(purpose), index);
}

// The two uniform doubles in (0, 1) one block holds: words (0, 1) and words (2, 3).
inline double first_uniform(const PhiloxWords& w) { return uniform01_double(w[0], w[1]); }
inline double second_uniform(const PhiloxWords& w) { return uniform01_double(w[2], w[3]); }

}  // namespace physarum
