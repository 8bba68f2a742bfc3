/* A STREAM-style triad on the device (opencl/runtime/memory_bandwidth.cpp; the host's is
 * common/numerics/memory_bandwidth.cpp): a = b + s c, one float4 per work-item, so every device reads and
 * writes whole lines in order and the rate is its memory's, not its arithmetic's. */
__kernel void triad(const uint n, __global float4* a, __global const float4* b, __global const float4* c,
                    const float s) {
  const uint i = get_global_id(0);
  if (i < n) a[i] = b[i] + s * c[i];
}
