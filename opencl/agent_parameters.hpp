#pragma once
// The agent parameters as the kernels read them: one PhysarumAgentParameters record per vertex (or
// one for the whole surface when every parameter is uniform), packed from the parameter table
// (common/model_parameters.hpp). The record's kernel-side struct and its interpolation are generated
// from the same table (agent_parameters_header), so a new agent parameter needs no edit here.
#include "common/vertex_parameters.hpp"
#include "kernels/device_types.h"

#include <string>
#include <vector>

namespace physarum::opencl {

static_assert(sizeof(PhysarumAgentParameters) == kAgentParamCount * sizeof(float),
              "PhysarumAgentParameters: one float per agent parameter of the table");

struct PackedAgentParameters {
  std::vector<PhysarumAgentParameters> per_vertex;  // in the order of `params`' vertices
  bool uniform = true;                              // every agent parameter has one value everywhere
};

// Packs every agent parameter of `params` in its device form (DeviceForm), as float.
PackedAgentParameters pack_agent_parameters(const VertexParameters& params);

// The kernels' "agent_parameters.h": the PhysarumAgentParameters struct with one named float per
// agent parameter (the table's device_name), and PHYSARUM_BLEND_AGENT_PARAMETERS(r, a, b, c, w),
// the barycentric interpolation r = w.x a + w.y b + w.z c field by field.
const std::string& agent_parameters_header();

}  // namespace physarum::opencl
