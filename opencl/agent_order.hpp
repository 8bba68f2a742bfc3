#pragma once
// Keeping agents in memory order of the faces they stand on (host side of kernels/agent_order.cl):
// a counting sort by device face, or by bins of 2^shift consecutive faces when there are more faces
// than kMaxBins, scattering into a second set of agent arrays that then takes the first's place.
// An order of work only: no result changes.
#include "opencl/agents.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace physarum::opencl {

class DeviceAgentOrder {
 public:
  static constexpr cl_uint kMaxBins = 65536;

  // Takes the sort's kernels from `program` (agent_step.cl, which includes agent_order.cl) and
  // allocates the bins and the spare agent arrays. agent_group is the local size of the per-agent
  // launches, agent_groups their number of groups.
  DeviceAgentOrder(const ComputeContext& compute, const cl::Program& program, int face_count, int agent_count,
                   std::size_t agent_group, std::size_t agent_groups);

  // Enqueues the sort of `agents` by face; on return `agents` names the sorted arrays.
  void enqueue_sort(DeviceAgents& agents);

  // The buffers the sort's kernels write (canary-guarded), for the out-of-bounds checks.
  std::vector<const DeviceBuffer*> written_buffers() const;

 private:
  ComputeContext compute_;
  cl::Kernel bin_counts_, bin_offsets_, scatter_;
  int agent_count_ = 0;
  std::size_t agent_group_ = 1, agent_groups_ = 1, scan_group_ = 1;
  cl_uint bin_shift_ = 0, bins_ = 1;
  DeviceBuffer bin_cursor_;
  DeviceAgents sorted_;  // the sort scatters into these, then swaps them with the caller's
};

}  // namespace physarum::opencl
