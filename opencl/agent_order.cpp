#include "opencl/agent_order.hpp"

#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/opencl_error.hpp"
#include "opencl/runtime/work_group_size.hpp"

#include <algorithm>
#include <utility>

namespace physarum::opencl {

DeviceAgentOrder::DeviceAgentOrder(const ComputeContext& compute, const cl::Program& program, int face_count,
                                   int agent_count, std::size_t agent_group, std::size_t agent_groups)
    : compute_(compute), agent_count_(agent_count), agent_group_(agent_group), agent_groups_(agent_groups) {
  try {
    bin_counts_ = cl::Kernel(program, "agent_bin_counts");
    bin_offsets_ = cl::Kernel(program, "agent_bin_offsets");
    scatter_ = cl::Kernel(program, "agent_scatter");
    scan_group_ = work_group_size(bin_offsets_, compute.device, 256, sizeof(cl_uint));
  } catch (const cl::Error& e) {
    throw device_error("preparing the agent sort kernels (agent_order.cl) on " + compute.device.device_name, e.err());
  }
  // One bin per device face, or per 2^shift faces, at most kMaxBins.
  const cl_uint faces = static_cast<cl_uint>(face_count);
  while ((faces + (1u << bin_shift_) - 1) >> bin_shift_ > kMaxBins) ++bin_shift_;
  bins_ = std::max<cl_uint>(1, (faces + (1u << bin_shift_) - 1) >> bin_shift_);
  sorted_ = DeviceAgents::allocate(compute, agent_count);
  bin_cursor_ = allocate_written<cl_uint>(compute, "agent sort bins", bins_);
}

void DeviceAgentOrder::enqueue_sort(DeviceAgents& agents) {
  if (agent_count_ == 0) return;
  const cl::NDRange agents_global(agent_groups_ * agent_group_), agents_local(agent_group_);
  cl::CommandQueue& queue = compute_.queue;
  queue.enqueueFillBuffer(bin_cursor_.buffer, cl_uint{0}, 0, bin_cursor_.payload_bytes);
  set_arguments(bin_counts_, static_cast<cl_int>(agent_count_), bin_shift_, agents.face, bin_cursor_);
  queue.enqueueNDRangeKernel(bin_counts_, cl::NullRange, agents_global, agents_local);
  set_arguments(bin_offsets_, bins_, bin_cursor_, cl::Local(scan_group_ * sizeof(cl_uint)));
  queue.enqueueNDRangeKernel(bin_offsets_, cl::NullRange, cl::NDRange(scan_group_), cl::NDRange(scan_group_));
  set_arguments(scatter_, static_cast<cl_int>(agent_count_), bin_shift_, bin_cursor_, agents.buffers(),
                sorted_.buffers());
  queue.enqueueNDRangeKernel(scatter_, cl::NullRange, agents_global, agents_local);
  std::swap(agents, sorted_);
}

std::vector<const DeviceBuffer*> DeviceAgentOrder::written_buffers() const {
  std::vector<const DeviceBuffer*> written = sorted_.buffers();
  written.push_back(&bin_cursor_);
  return written;
}

}  // namespace physarum::opencl
