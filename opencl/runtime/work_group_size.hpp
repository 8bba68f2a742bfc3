#pragma once
// Choosing launch sizes from what the device and the compiled kernel allow, never a fixed number:
// a CPU driver may allow 4096 work-items per group, a small GPU 256, an emulator 1.
#include "opencl/runtime/device_selection.hpp"
#include "opencl/runtime/opencl_api.hpp"

#include <algorithm>
#include <cstddef>
#include <initializer_list>

namespace physarum::opencl {

// The largest power of two <= min(cap, the kernel's CL_KERNEL_WORK_GROUP_SIZE, the device maximum,
// what `local_bytes_per_item` of local memory per work-item leaves room for). Power of two because
// the tree reductions halve the group. At least 1.
inline std::size_t work_group_size(const cl::Kernel& kernel, const DeviceInfo& device, std::size_t cap = 256,
                                   std::size_t local_bytes_per_item = 0) {
  std::size_t limit = std::min(cap, device.max_work_group_size);
  limit = std::min(limit, kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device.device));
  if (local_bytes_per_item > 0) {
    const std::size_t local_memory = device.device.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
    limit = std::min(limit, local_memory / local_bytes_per_item);
  }
  std::size_t size = 1;
  while (size * 2 <= limit) size *= 2;
  return size;
}

// One local size that every kernel of `kernels` allows (the smallest work_group_size of them), so
// kernels that share partial sums or buffers of per-group results launch alike.
inline std::size_t common_work_group_size(std::initializer_list<const cl::Kernel*> kernels, const DeviceInfo& device,
                                          std::size_t cap = 256, std::size_t local_bytes_per_item = 0) {
  std::size_t size = cap;
  for (const cl::Kernel* kernel : kernels)
    size = std::min(size, work_group_size(*kernel, device, cap, local_bytes_per_item));
  return size;
}

// n rounded up to a multiple of group (the kernels guard the padding with `if (i >= n) return;`).
inline std::size_t padded_global_size(std::size_t n, std::size_t group) {
  return std::max<std::size_t>(group, (n + group - 1) / group * group);
}

}  // namespace physarum::opencl
