#pragma once
// Rules of the agent model that both backends implement and that are not parameters: the bounds
// of a turn decision, and the hazard rate that turnover integrates (paper Sec. 3.2-3.3). The
// kernels' copies (kernels/device_types.h) are checked against these at compile time
// (opencl/agent_simulation.cpp).
#include "common/base/element_data.hpp"

namespace physarum {

// At most this many turn decisions fall in one step (one per word of a Philox block); a time step
// that long is far beyond the decision period the paper considers meaningful (Sec. 4, Fig. 10d).
constexpr int kMaxTurnDecisionsPerStep = 4;

// A decision is due when the clock is within this fraction of dt of the period (rounding slack;
// see reference/sensing_steering.cpp). The same value is PHYSARUM_TURN_DECISION_TOLERANCE in the kernels.
constexpr double kTurnDecisionTolerance = 1e-4;

// Hazard rate 1/tau per vertex: 0 where tau is infinite (no turnover), +infinity where tau is 0 (a
// sink). Interpolating the hazard rather than tau keeps both ends finite-safe. It is the device form
// of mean_lifetime in the parameter table (DeviceForm::Reciprocal), so both backends agree.
IntrinsicVertexData<double> hazard_rate_per_vertex(const IntrinsicVertexData<double>& mean_lifetime);

}  // namespace physarum
