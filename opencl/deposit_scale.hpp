#pragma once
// The fixed-point scale of the device's deposit accumulator (kernels/deposition.cl): deposits add
// round(amount * scale) as 64-bit integers, so their sum does not depend on the order of the adds.
#include <vector>


#include "common/base/element_data.hpp"
#include "opencl/runtime/device_selection.hpp"

namespace physarum::opencl {

// Deposits accumulate in 64-bit fixed point where the device has 64-bit atomics
// (cl_khr_int64_base_atomics), in floats by compare-and-swap elsewhere (kernels/deposit_cells.h).
inline bool fixed_point_deposits(const DeviceInfo& device) { return device.int64_atomics; }

// 2^k with k the largest (at most 60) that keeps `largest_total` at or below 2^62 units; 2^40 when
// largest_total is 0.
double fixed_point_scale_for(double largest_total);

// 2^k with k the largest (at most 60) that keeps the worst case of one step, every agent's whole
// deposit max(deposit_rate) * time_step into one vertex, at or below 2^62; 2^40 when nothing is
// deposited. Throws InputError when even that scale leaves fewer than 2^20 units for one agent's
// deposit of one step at the smallest positive rate (rounding would then matter at the 1e-6 level).
double fixed_point_deposit_scale(const IntrinsicVertexData<double>& deposit_rate, int agent_count, double time_step);

}  // namespace physarum::opencl
