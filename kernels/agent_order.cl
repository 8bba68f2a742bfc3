/* Keeping agents in memory order of the faces they stand on (a counting sort by device face, or by
 * a bin of 2^shift consecutive device faces when there are more faces than bins). Agents next to
 * each other in the arrays then walk over the same face records, which stay in cache: on a mesh
 * larger than the cache this is the difference between a cache hit and a memory round trip at every
 * face crossing. The reference has no counterpart: it is an order of work, not part of the model.
 *
 * The order within one bin depends on the timing of atomic increments, but nothing an agent computes
 * depends on its slot: its random streams are keyed by its id, and deposits add in fixed point, which
 * does not depend on the order. The sort changes no result. */
#include "device_types.h"

__kernel void agent_bin_counts(const int agent_count, const uint bin_shift, __global const int* face,
                               __global uint* counts) {
  const int a = get_global_id(0);
  if (a >= agent_count) return;
  atomic_inc(&counts[(uint)face[a] >> bin_shift]);
}

/* Exclusive prefix sum of `bins` counts, in ONE work-group: each work-item adds a contiguous chunk
 * (a bounded loop), the group scans the chunk sums in local memory, each work-item writes its
 * chunk's offsets. counts become the running insertion cursors of agent_scatter. */
__kernel void agent_bin_offsets(const uint bins, __global uint* counts, __local uint* chunk_sum) {
  const uint lid = get_local_id(0), size = get_local_size(0);
  const uint chunk = (bins + size - 1) / size;
  const uint begin = min(lid * chunk, bins), end = min(begin + chunk, bins);
  uint sum = 0u;
  for (uint b = begin; b < end; ++b) sum += counts[b];
  chunk_sum[lid] = sum;
  barrier(CLK_LOCAL_MEM_FENCE);
  /* Hillis-Steele inclusive scan of the chunk sums. */
  for (uint stride = 1; stride < size; stride <<= 1) {
    const uint add = lid >= stride ? chunk_sum[lid - stride] : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    chunk_sum[lid] += add;
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  uint offset = chunk_sum[lid] - sum;
  for (uint b = begin; b < end; ++b) {
    const uint c = counts[b];
    counts[b] = offset;
    offset += c;
  }
}

__kernel void agent_scatter(const int agent_count, const uint bin_shift, __global uint* cursor,
                            __global const int* face, __global const float2* position, __global const float2* heading,
                            __global const float* age, __global const float* exposure,
                            __global const float* exposure_threshold, __global const float* time_since_decision,
                            __global const float* accumulated_turn, __global const uint* id,
                            __global int* face_out, __global float2* position_out, __global float2* heading_out,
                            __global float* age_out, __global float* exposure_out,
                            __global float* exposure_threshold_out, __global float* time_since_decision_out,
                            __global float* accumulated_turn_out, __global uint* id_out) {
  const int a = get_global_id(0);
  if (a >= agent_count) return;
  const int f = face[a];
  const uint slot = atomic_inc(&cursor[(uint)f >> bin_shift]);
  face_out[slot] = f;
  position_out[slot] = position[a];
  heading_out[slot] = heading[a];
  age_out[slot] = age[a];
  exposure_out[slot] = exposure[a];
  exposure_threshold_out[slot] = exposure_threshold[a];
  time_since_decision_out[slot] = time_since_decision[a];
  accumulated_turn_out[slot] = accumulated_turn[a];
  id_out[slot] = id[a];
}
