#pragma once
// Field statistics reduced on the device (mirrors common/simulation/field_statistics): the area-weighted mean
// and the coverage fractions above kCoverageMultiples x U, from a float field that stays on the
// device. Only four floats come back per call. Sums run in a fixed order (work-group tree, then one
// group over the partials), so repeated calls on one device give identical results.
#include "common/simulation/field_statistics.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"

#include <array>
#include <string>
#include <vector>

namespace physarum::opencl {

class DeviceFieldStatistics {
 public:
  // mass: the lumped vertex masses on the device (float, vertex_count of them); the handle is kept.
  // Builds reduction.cl and sums the total mass once, with the same kernels, so a field above every
  // threshold reports a coverage of exactly 1.
  DeviceFieldStatistics(const ComputeContext& compute, const cl::Buffer& mass, int vertex_count);

  // values: one float per vertex on the device.
  FieldStatistics compute(const cl::Buffer& values, double U) const;
  // sum_i m_i u_i.
  double weighted_sum(const cl::Buffer& values) const;
  double total_mass() const { return total_mass_; }

  // Names of the buffers these kernels wrote past (empty when all canaries are intact).
  std::vector<std::string> damaged_canaries() const;

 private:
  // [0] sum m u, [1..3] mass above thresholds[0..2].
  std::array<double, 4> sums(const cl::Buffer& values, const std::array<float, 3>& thresholds) const;

  ComputeContext compute_;
  cl::Buffer mass_;
  int vertex_count_ = 0;
  mutable cl::Kernel partial_kernel_, final_kernel_;  // setArg mutates the kernel object
  std::size_t partial_group_ = 1, final_group_ = 1, group_count_ = 1;
  DeviceBuffer partials_, result_;
  double total_mass_ = 0.0;
};

}  // namespace physarum::opencl
