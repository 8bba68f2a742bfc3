#pragma once
// The agents' parameters as the kernels read them (PhysarumAgentParameters, kernels/device_types.h):
// one record per vertex, and whether they are all one value (then the kernels read the uniform
// record of PhysarumStepConstants instead of interpolating).
#include "common/vertex_parameters.hpp"
#include "kernels/device_types.h"

#include <vector>

namespace physarum::opencl {

struct PackedAgentParameters {
  std::vector<PhysarumAgentParameters> per_vertex;  // in the order of params' vertices
  bool uniform = true;                              // every agent parameter map is one value
};

// Packs params (any vertex order; the device's, for the upload) into float records, the hazard rate
// from the mean lifetime as the reference's turnover computes it.
PackedAgentParameters pack_agent_parameters(const VertexParameters& params);

}  // namespace physarum::opencl
