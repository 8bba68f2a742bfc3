#pragma once
// The whole evolving state of a simulation, as a backend hands it out for a checkpoint and takes it
// back on resume (common/run/checkpoint.hpp): what one step reads that a fresh backend built from the same
// scene does not already hold. Everything else a backend owns (geometry, operators, parameters,
// spawn tables, compiled kernels) is rebuilt from the scene, so it is not stored.
//
// Randomness needs no state of its own: every draw is a Philox block keyed (seed, agent) with
// counter (step, purpose) (common/base/random_streams.hpp), so the step count *is* the random streams'
// position and restoring it restores every stream.
//
// A backend without agents (a reaction–diffusion system) fills only the layers, the step and the
// time, and leaves `agents` empty: the format does not assume agents exist.
#include "common/model/agents.hpp"
#include "common/base/element_data.hpp"
#include "common/simulation/simulation_backend.hpp"

#include <vector>

namespace physarum {

struct SimulationState {
  long long steps_taken = 0;
  // Simulated seconds, stored as the backend keeps them: the reference sums dt step by step, and
  // steps_taken * dt can differ from that sum in the last bit.
  double time = 0.0;
  // Every layer, dynamic and static, in layer order, per intrinsic vertex in the domain's order.
  std::vector<IntrinsicVertexData<double>> layers;
  // Every agent in id order (empty for a backend without agents).
  Agents agents;
  // The running totals of run.json.
  SimulationCounters counters;
  // What a model whose surface changes as it runs needs to rebuild it (the growth model's sheet:
  // shape, rest state, carried maps, step records), in that model's own layout (api/growth_simulation.cpp);
  // empty for the others.
  std::vector<std::vector<double>> model_arrays;
};

}  // namespace physarum
