#pragma once
// The bandwidth of host memory, for the roofline of kernels that run from it (the reference, and
// OpenCL on a CPU device): a STREAM-style triad a = b + s c over three arrays far larger than any
// cache, one thread per core. opencl/runtime/memory_bandwidth.hpp measures a device's own memory the same way.
#include <cstddef>
#include <vector>

namespace physarum {

class HostTriad {
 public:
  HostTriad();
  // Bytes per second, the best of `repeats` triads (2 reads + 1 write per element; the write's
  // cache-line fill is not counted, as STREAM does not). The arrays are kept, so timings can be put
  // beside a triad taken the moment before: on a shared machine a bandwidth measured minutes away
  // says little about the one a kernel had.
  double bytes_per_second(int repeats);
  // What one triad moves, by the count above.
  double bytes_per_triad() const { return 3.0 * static_cast<double>(a_.size()) * sizeof(double); }

 private:
  std::vector<double> a_, b_, c_;
};

}  // namespace physarum
