#pragma once
// The bandwidth of a device's own memory (mirrors common/numerics/memory_bandwidth.hpp, the host's): a
// STREAM-style triad a = b + s c in kernels/memory_bandwidth.cl over three arrays of at least 64 MB
// and four times the device's global-memory cache, so that a GPU's L2 does not answer for its memory.
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"

#include <cstddef>

namespace physarum::opencl {

class DeviceTriad {
 public:
  // Throws DeviceError when the arrays do not fit the device (each within its largest allocation,
  // all three within half its memory).
  explicit DeviceTriad(const ComputeContext& compute);
  // Bytes per second, the best of `repeats` timings of launches_ triads back to back
  // (DeviceTuning::triad_launches: ten on a GPU, so its launch latency does not count; one on a
  // CPU, where a triad takes milliseconds); 2 reads + 1 write per element, as the host's triad counts.
  double bytes_per_second(int repeats);
  double bytes_per_triad() const { return 3.0 * static_cast<double>(elements_) * 16.0; }
  // Reads a back: true when every element is b + s c of the last triad (for the tests).
  bool result_is_correct() const;

 private:
  ComputeContext compute_;
  std::size_t elements_ = 0;  // float4 per array
  cl::Kernel kernel_;
  std::size_t group_ = 1;
  int launches_ = 1;
  DeviceBuffer a_, b_, c_;
};

}  // namespace physarum::opencl
