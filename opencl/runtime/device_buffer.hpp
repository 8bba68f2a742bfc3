#pragma once
// Device buffers that know their name (for messages), are checked against the device's largest
// allocation before they are made, and, when written by kernels, carry a canary region after the
// payload so a kernel that writes past its range is caught (tests ask damaged_canaries()).
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/opencl_api.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace physarum::opencl {

// 64 bytes of canary: more than one float4 element, so an off-by-one write of any element type lands in it.
inline constexpr std::size_t kCanaryBytes = 64;
inline constexpr std::uint8_t kCanaryByte = 0xA5;

struct DeviceBuffer {
  cl::Buffer buffer;
  std::string name;
  std::size_t payload_bytes = 0;
  bool guarded = false;  // a canary region follows the payload
  std::shared_ptr<void> host_memory;  // the memory behind a CL_MEM_USE_HOST_PTR buffer, kept alive with it
};

// Allocates payload_bytes (+ kCanaryBytes when guarded, with the canary written). Throws DeviceError
// naming the buffer, its size and the device's limit when the size exceeds max_allocation_bytes,
// and a DeviceError with the OpenCL error name when the allocation itself fails.
DeviceBuffer allocate_buffer(const ComputeContext& compute, const std::string& name, std::size_t payload_bytes,
                             cl_mem_flags flags, bool guarded);

// allocate_buffer for `count` elements of T (no byte arithmetic at the call site). Guarded and
// read-write: what kernels write.
template <class T>
DeviceBuffer allocate_written(const ComputeContext& compute, const std::string& name, std::size_t count) {
  return allocate_buffer(compute, name, count * sizeof(T), CL_MEM_READ_WRITE, true);
}

// allocate_buffer + a blocking upload of `values`.
template <class T>
DeviceBuffer upload_buffer(const ComputeContext& compute, const std::string& name, const std::vector<T>& values,
                           cl_mem_flags flags, bool guarded) {
  DeviceBuffer b = allocate_buffer(compute, name, values.size() * sizeof(T), flags, guarded);
  if (!values.empty()) compute.queue.enqueueWriteBuffer(b.buffer, CL_TRUE, 0, b.payload_bytes, values.data());
  return b;
}

// Read-only data that kernels read at random places (face records). Where the device's tuning asks
// for it (DeviceTuning::huge_page_random_access: CPU devices) the buffer lives in host memory
// aligned to 2 MiB and marked for transparent huge pages (Linux madvise), so random reads across
// tens of megabytes miss the TLB far less: the page walks of 4 KiB pages are dear, in a virtual
// machine doubly so (bench/README.md, "Tuning measurements"). Other devices, or where huge pages
// are not offered: upload_buffer.
DeviceBuffer upload_random_access_buffer(const ComputeContext& compute, const std::string& name, const void* data,
                                         std::size_t bytes);
template <class T>
DeviceBuffer upload_random_access_buffer(const ComputeContext& compute, const std::string& name,
                                         const std::vector<T>& values) {
  return upload_random_access_buffer(compute, name, values.data(), values.size() * sizeof(T));
}

// Reads the canary back (blocking); true for an unguarded buffer.
bool canary_intact(const ComputeContext& compute, const DeviceBuffer& buffer);

}  // namespace physarum::opencl
