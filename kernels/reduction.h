/* Work-group tree reduction shared by reduction.cl and conjugate_gradients.cl. A fixed local size
 * gives a fixed summation order, so the result is deterministic on a given device. */
#ifndef PHYSARUM_REDUCTION_H
#define PHYSARUM_REDUCTION_H

/* Sum of v over the work-group, returned to every work-item. The local size must be a power of two
 * and every work-item must call this (it holds barriers): callers that have no element pass 0. The
 * leading barrier lets a kernel call it more than once with the same scratch. */
float4 work_group_sum4(__local float4* scratch, const float4 v) {
  const uint lid = get_local_id(0);
  barrier(CLK_LOCAL_MEM_FENCE);
  scratch[lid] = v;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint stride = get_local_size(0) / 2; stride > 0; stride >>= 1) {
    if (lid < stride) scratch[lid] += scratch[lid + stride];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  return scratch[0];
}

/* Second pass, run by ONE work-group: the sum of `count` per-group partials. Each work-item first
 * adds a strided slice (a bounded loop), then the group reduces those. */
float4 sum_partials4(__global const float4* partials, const uint count, __local float4* scratch) {
  float4 acc = (float4)(0.0f);
  for (uint k = get_local_id(0); k < count; k += get_local_size(0)) acc += partials[k];
  return work_group_sum4(scratch, acc);
}

#endif /* PHYSARUM_REDUCTION_H */
