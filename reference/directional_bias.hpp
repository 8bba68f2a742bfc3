#pragma once
// Directional bias (paper Sec. 3.3, Fig. 6) in the serial reference: after sensing and steering,
// every agent's heading relaxes toward the closest copy of the local bias direction
// (common/model/directional_bias.hpp has the rule; kernels/bias.cl is the device side).
#include "common/model/agents.hpp"
#include "common/model/simulation_controls.hpp"
#include "common/surface/surface_domain.hpp"

namespace physarum {

// Turns every agent by one step of length dt of the bias: direction of its face, strength
// interpolated at its position.
void apply_directional_bias(const SurfaceDomain& domain, const DirectionalBias& bias, double dt, Agents& agents);

}  // namespace physarum
