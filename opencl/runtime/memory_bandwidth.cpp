#include "opencl/runtime/memory_bandwidth.hpp"

#include "common/base/errors.hpp"
#include "opencl/runtime/device_tuning.hpp"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/kernel_sources.hpp"
#include "opencl/runtime/opencl_error.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "opencl/runtime/work_group_size.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <vector>

namespace physarum::opencl {
namespace {

constexpr float kB = 1.0f, kC = 2.0f, kS = 3.0f;  // a = kB + kS kC, exact in float

}  // namespace

DeviceTriad::DeviceTriad(const ComputeContext& compute) : compute_(compute) {
  const DeviceInfo& d = compute.device;
  const std::uint64_t wanted = std::max<std::uint64_t>(64u << 20, 4 * d.global_cache_bytes);
  const std::uint64_t fits = std::min<std::uint64_t>(d.max_allocation_bytes, d.global_memory_bytes / 6);
  const std::uint64_t bytes = std::min(wanted, fits) / 16 * 16;
  if (bytes < (1u << 20) || bytes / 16 > std::numeric_limits<cl_uint>::max())
    throw DeviceError("memory bandwidth: three triad arrays of " + std::to_string(wanted >> 20) + " MiB do not fit " +
                      d.device_name + " (largest allocation " + std::to_string(d.max_allocation_bytes >> 20) +
                      " MiB, memory " + std::to_string(d.global_memory_bytes >> 20) + " MiB)");
  elements_ = static_cast<std::size_t>(bytes / 16);
  launches_ = tuning_for(d).triad_launches;
  try {
    const cl::Program program =
        build_program(compute.context, compute.device, "memory_bandwidth.cl", kernel_source("memory_bandwidth.cl"));
    kernel_ = cl::Kernel(program, "triad");
    group_ = work_group_size(kernel_, compute.device, 256, 0);
  } catch (const cl::Error& e) {
    throw device_error("preparing the triad kernel (memory_bandwidth.cl) on " + d.device_name, e.err());
  }
  a_ = allocate_buffer(compute, "triad a", bytes, CL_MEM_WRITE_ONLY, false);
  b_ = upload_buffer(compute, "triad b", std::vector<float>(elements_ * 4, kB), CL_MEM_READ_ONLY, false);
  c_ = upload_buffer(compute, "triad c", std::vector<float>(elements_ * 4, kC), CL_MEM_READ_ONLY, false);
}

double DeviceTriad::bytes_per_second(int repeats) {
  using Clock = std::chrono::steady_clock;
  double best = 0.0;
  try {
    set_arguments(kernel_, static_cast<cl_uint>(elements_), a_, b_, c_, kS);
    const cl::NDRange global(padded_global_size(elements_, group_)), local(group_);
    compute_.queue.enqueueNDRangeKernel(kernel_, cl::NullRange, global, local);  // first touch, not timed
    compute_.queue.finish();
    for (int repeat = 0; repeat < repeats; ++repeat) {
      const Clock::time_point start = Clock::now();
      for (int launch = 0; launch < launches_; ++launch)
        compute_.queue.enqueueNDRangeKernel(kernel_, cl::NullRange, global, local);
      compute_.queue.finish();
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      best = std::max(best, launches_ * bytes_per_triad() / seconds);
    }
  } catch (const cl::Error& e) {
    throw device_error("timing the triad on " + compute_.device.device_name, e.err());
  }
  return best;
}

bool DeviceTriad::result_is_correct() const {
  std::vector<float> a(elements_ * 4);
  try {
    compute_.queue.enqueueReadBuffer(a_.buffer, CL_TRUE, 0, a.size() * sizeof(float), a.data());
  } catch (const cl::Error& e) {
    throw device_error("reading the triad back from " + compute_.device.device_name, e.err());
  }
  return std::all_of(a.begin(), a.end(), [](float x) { return x == kB + kS * kC; });
}

}  // namespace physarum::opencl
