// Known-answer check of the device's Philox4x32-10: the same Random123 header the host uses,
// compiled as OpenCL C. One work-item per (counter, key) pair.
#include <Random123/philox.h>

__kernel void philox_known_answers(__global const uint4* counters, __global const uint2* keys,
                                   __global uint4* results, const uint count) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  philox4x32_ctr_t c = {{counters[i].x, counters[i].y, counters[i].z, counters[i].w}};
  philox4x32_key_t k = {{keys[i].x, keys[i].y}};
  const philox4x32_ctr_t r = philox4x32_R(10, c, k);
  results[i] = (uint4)(r.v[0], r.v[1], r.v[2], r.v[3]);
}
