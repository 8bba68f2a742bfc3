#pragma once
// The agent population on the device (the state of common/model/agents.hpp, plus each agent's id): one buffer per attribute
// (structure of arrays), plus each agent's id, the key of its random streams, so agents can be
// reordered in memory without changing what they draw. The host-side exchange type is the
// reference's Agents, so tests can hand identical states to both backends.
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "common/model/agents.hpp"

#include <string>
#include <vector>

namespace physarum::opencl {

struct DeviceAgents {
  int count = 0;
  DeviceBuffer face, position, heading, age, exposure, exposure_threshold, time_since_decision, accumulated_turn, id;

  // Allocates every buffer for `count` agents (canary-guarded: kernels write them). Throws
  // DeviceError naming the buffer, the agent count and the device limit when one does not fit.
  static DeviceAgents allocate(const ComputeContext& compute, int count);

  // Blocking upload of host states (converted to float); agent a gets id a.
  void upload(const ComputeContext& compute, const Agents& agents) const;
  // Blocking download, converted to double and put back in id order.
  Agents download(const ComputeContext& compute) const;
  // The faces alone, in id order.
  std::vector<int> download_faces(const ComputeContext& compute) const;

  std::vector<const DeviceBuffer*> buffers() const;
};

}  // namespace physarum::opencl
