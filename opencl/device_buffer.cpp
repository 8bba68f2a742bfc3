#include "opencl/device_buffer.hpp"

#include "opencl/opencl_error.hpp"

#include <algorithm>

namespace physarum::opencl {

DeviceBuffer allocate_buffer(const ComputeContext& compute, const std::string& name, std::size_t payload_bytes,
                             cl_mem_flags flags, bool guarded) {
  DeviceBuffer b;
  b.name = name;
  b.payload_bytes = payload_bytes;
  b.guarded = guarded;
  // OpenCL refuses zero-sized buffers; an empty payload still gets one word.
  const std::size_t bytes = std::max<std::size_t>(payload_bytes + (guarded ? kCanaryBytes : 0), 4);
  if (bytes > compute.device.max_allocation_bytes)
    throw DeviceError("device buffer '" + name + "' needs " + std::to_string(bytes) +
                      " bytes, more than the largest allocation " + compute.device.device_name + " allows (" +
                      std::to_string(compute.device.max_allocation_bytes) +
                      " bytes); try a coarser surface or another device");
  try {
    b.buffer = cl::Buffer(compute.context, flags, bytes);
    if (guarded) {
      const std::vector<std::uint8_t> canary(kCanaryBytes, kCanaryByte);
      compute.queue.enqueueWriteBuffer(b.buffer, CL_TRUE, payload_bytes, kCanaryBytes, canary.data());
    }
  } catch (const cl::Error& e) {
    throw device_error("allocating device buffer '" + name + "' of " + std::to_string(bytes) + " bytes on " +
                           compute.device.device_name,
                       e.err());
  }
  return b;
}

bool canary_intact(const ComputeContext& compute, const DeviceBuffer& buffer) {
  if (!buffer.guarded) return true;
  std::vector<std::uint8_t> canary(kCanaryBytes);
  compute.queue.enqueueReadBuffer(buffer.buffer, CL_TRUE, buffer.payload_bytes, kCanaryBytes, canary.data());
  return std::all_of(canary.begin(), canary.end(), [](std::uint8_t c) { return c == kCanaryByte; });
}

}  // namespace physarum::opencl
