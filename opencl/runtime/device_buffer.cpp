#include "opencl/runtime/device_buffer.hpp"

#include "opencl/runtime/device_tuning.hpp"
#include "opencl/runtime/opencl_error.hpp"

#include <algorithm>
#include <cstring>

#ifdef __linux__
#include <sys/mman.h>
#endif

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

DeviceBuffer upload_random_access_buffer(const ComputeContext& compute, const std::string& name, const void* data,
                                         std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  if (tuning_for(compute.device).huge_page_random_access && bytes >= kHugePage &&
      bytes <= compute.device.max_allocation_bytes) {
    // Fresh pages from mmap (a heap block may reuse pages already faulted in small), aligned by
    // over-allocating one huge page, and marked before the first write so they are huge from the
    // start. Where mmap or madvise fail, the ordinary buffer below serves.
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    const std::size_t mapped = rounded + kHugePage;
    void* region = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    std::shared_ptr<void> mapping(region == MAP_FAILED ? nullptr : region, [mapped](void* p) {
      if (p) munmap(p, mapped);
    });
    const auto address = reinterpret_cast<std::uintptr_t>(region);
    void* aligned = reinterpret_cast<void*>((address + kHugePage - 1) / kHugePage * kHugePage);
    std::shared_ptr<void> memory(mapping, aligned);  // shares the mapping's lifetime
    if (mapping && madvise(aligned, rounded, MADV_HUGEPAGE) == 0) {
      std::memcpy(memory.get(), data, bytes);
      DeviceBuffer b;
      b.name = name;
      b.payload_bytes = bytes;
      b.host_memory = memory;
      try {
        b.buffer = cl::Buffer(compute.context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes, memory.get());
      } catch (const cl::Error& e) {
        throw device_error("allocating device buffer '" + name + "' of " + std::to_string(bytes) + " bytes on " +
                               compute.device.device_name,
                           e.err());
      }
      return b;
    }
  }
#endif
  DeviceBuffer b = allocate_buffer(compute, name, bytes, CL_MEM_READ_ONLY, false);
  if (bytes > 0) compute.queue.enqueueWriteBuffer(b.buffer, CL_TRUE, 0, bytes, data);
  return b;
}

bool canary_intact(const ComputeContext& compute, const DeviceBuffer& buffer) {
  if (!buffer.guarded) return true;
  std::vector<std::uint8_t> canary(kCanaryBytes);
  compute.queue.enqueueReadBuffer(buffer.buffer, CL_TRUE, buffer.payload_bytes, kCanaryBytes, canary.data());
  return std::all_of(canary.begin(), canary.end(), [](std::uint8_t c) { return c == kCanaryByte; });
}

}  // namespace physarum::opencl
