/* Field statistics on the device (mirrors common/simulation/field_statistics): the area-weighted mean and the
 * coverage fractions need sum m_i u_i and sum over {u_i > t_k} of m_i. Pass 1 leaves one float4 per
 * work-group; pass 2 (one work-group) adds those in a fixed order. The host divides by the total
 * mass, itself summed by these kernels with thresholds of -infinity. */
#include "device_types.h"
#include "reduction.h"

__kernel void field_partial_sums(const uint n, __global const float* values, __global const float* mass,
                                 const float4 thresholds, /* .x .y .z: the coverage thresholds; .w unused */
                                 __global float4* partials, __local float4* scratch) {
  const uint i = get_global_id(0);
  float4 mine = (float4)(0.0f);
  /* No early return: every work-item must reach the barriers of the reduction. */
  if (i < n) {
    const float u = values[i];
    const float m = mass[i];
    mine = (float4)(m * u, u > thresholds.x ? m : 0.0f, u > thresholds.y ? m : 0.0f, u > thresholds.z ? m : 0.0f);
  }
  const float4 total = work_group_sum4(scratch, mine);
  if (get_local_id(0) == 0) partials[get_group_id(0)] = total;
}

__kernel void field_final_sums(const uint count, __global const float4* partials, __global float4* result,
                               __local float4* scratch) {
  const float4 total = sum_partials4(partials, count, scratch);
  if (get_global_id(0) == 0) result[0] = total;
}
