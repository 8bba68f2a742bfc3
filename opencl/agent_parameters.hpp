#pragma once
// The agent parameters as the kernels read them: one PhysarumAgentParameters record per vertex (or
// one for the whole surface when every parameter is uniform), packed from the parameter table
// (common/model/model_parameters.hpp). The record's kernel-side struct and its interpolation are generated
// from the same table (agent_parameters_header), so a new agent parameter needs no edit here.
#include "common/model/vertex_parameters.hpp"
#include "kernels/device_types.h"

#include <string>
#include <vector>

namespace physarum::opencl {

static_assert(sizeof(PhysarumAgentParameters) == kAgentParamCount * sizeof(float),
              "PhysarumAgentParameters: one float per agent parameter of the table");

struct PackedAgentParameters {
  std::vector<PhysarumAgentParameters> per_vertex;  // in the order of `params`' vertices
  bool uniform = true;                              // every agent parameter has one value everywhere
  // The build options naming the parameters that vary (-DPHYSARUM_MAPPED_<device_name>=1): only
  // those are interpolated in the kernels, the others are read from the step constants, so one map
  // on the sensor distance does not make the lifetime cost three vertex reads per agent.
  std::string mapped_build_options;
};

// Packs every agent parameter of `params` in its device form (DeviceForm), as float.
PackedAgentParameters pack_agent_parameters(const VertexParameters& params);

// The build options marking every agent parameter as mapped: competing species each read their own
// records, so a parameter uniform within every species may still differ between them.
std::string every_parameter_mapped_build_options();

// The kernels' "agent_parameters.h": the PhysarumAgentParameters struct with one named float per
// agent parameter (the table's device_name), and PHYSARUM_BLEND_MAPPED_AGENT_PARAMETERS(r, a, b, c,
// w), which sets each MAPPED parameter (PHYSARUM_MAPPED_<name> = 1: mapped_build_options) to the
// barycentric interpolation w.x a + w.y b + w.z c and leaves the others as they are in r.
const std::string& agent_parameters_header();

}  // namespace physarum::opencl
