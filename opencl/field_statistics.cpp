#include "opencl/field_statistics.hpp"

#include "kernels/device_types.h"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/kernel_sources.hpp"
#include "opencl/runtime/opencl_error.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "opencl/runtime/work_group_size.hpp"

#include <limits>

namespace physarum::opencl {

static_assert(PHYSARUM_FIELD_SUM_COMPONENTS == 4 && PHYSARUM_COVERAGE_THRESHOLDS == kCoverageMultiples.size(),
              "reduction.cl sums one weighted total and one mass per coverage multiple, as a float4");

DeviceFieldStatistics::DeviceFieldStatistics(const ComputeContext& compute, const cl::Buffer& mass, int vertex_count)
    : compute_(compute), mass_(mass), vertex_count_(vertex_count) {
  if (vertex_count <= 0) throw InputError("device statistics: the field has " + std::to_string(vertex_count) + " vertices");
  try {
    const cl::Program program =
        build_program(compute.context, compute.device, "reduction.cl", kernel_source("reduction.cl"));
    partial_kernel_ = cl::Kernel(program, "field_partial_sums");
    final_kernel_ = cl::Kernel(program, "field_final_sums");
    partial_group_ = work_group_size(partial_kernel_, compute.device, 256, sizeof(cl_float4));
    final_group_ = work_group_size(final_kernel_, compute.device, 256, sizeof(cl_float4));
  } catch (const cl::Error& e) {
    throw device_error("preparing the statistics kernels (reduction.cl)", e.err());
  }
  group_count_ = padded_global_size(static_cast<std::size_t>(vertex_count), partial_group_) / partial_group_;
  partials_ = allocate_written<cl_float4>(compute, "statistics partial sums", group_count_);
  result_ = allocate_written<cl_float4>(compute, "statistics result", 1);
  const float below_everything = -std::numeric_limits<float>::infinity();
  total_mass_ = sums(mass_, {below_everything, below_everything, below_everything})[1];
  if (!(total_mass_ > 0.0))
    throw InputError("device statistics: total vertex mass " + std::to_string(total_mass_) + " is not > 0");
}

std::array<double, 4> DeviceFieldStatistics::sums(const cl::Buffer& values, const std::array<float, 3>& thresholds) const {
  const cl_uint n = static_cast<cl_uint>(vertex_count_);
  const cl_uint groups = static_cast<cl_uint>(group_count_);
  const cl_float4 t = {{thresholds[0], thresholds[1], thresholds[2], 0.0f}};
  cl_float4 out{};
  try {
    set_arguments(partial_kernel_, n, values, mass_, t, partials_, cl::Local(partial_group_ * sizeof(cl_float4)));
    compute_.queue.enqueueNDRangeKernel(partial_kernel_, cl::NullRange, cl::NDRange(group_count_ * partial_group_),
                                        cl::NDRange(partial_group_));
    set_arguments(final_kernel_, groups, partials_, result_, cl::Local(final_group_ * sizeof(cl_float4)));
    compute_.queue.enqueueNDRangeKernel(final_kernel_, cl::NullRange, cl::NDRange(final_group_), cl::NDRange(final_group_));
    compute_.queue.enqueueReadBuffer(result_.buffer, CL_TRUE, 0, sizeof(cl_float4), &out);
  } catch (const cl::Error& e) {
    throw device_error("reducing field statistics on " + compute_.device.device_name, e.err());
  }
  return {out.s[0], out.s[1], out.s[2], out.s[3]};
}

FieldStatistics DeviceFieldStatistics::compute(const cl::Buffer& values, double U) const {
  std::array<float, 3> thresholds{};
  for (size_t k = 0; k < kCoverageMultiples.size(); ++k) thresholds[k] = static_cast<float>(kCoverageMultiples[k] * U);
  const std::array<double, 4> s = sums(values, thresholds);
  FieldStatistics stats;
  stats.mean = s[0] / total_mass_;
  stats.U = U;
  for (size_t k = 0; k < kCoverageMultiples.size(); ++k) stats.coverage[k] = s[k + 1] / total_mass_;
  return stats;
}

double DeviceFieldStatistics::weighted_sum(const cl::Buffer& values) const {
  const float above_nothing = std::numeric_limits<float>::infinity();
  return sums(values, {above_nothing, above_nothing, above_nothing})[0];
}

std::vector<std::string> DeviceFieldStatistics::damaged_canaries() const {
  std::vector<std::string> damaged;
  for (const DeviceBuffer* b : {&partials_, &result_})
    if (!canary_intact(compute_, *b)) damaged.push_back(b->name);
  return damaged;
}

}  // namespace physarum::opencl
