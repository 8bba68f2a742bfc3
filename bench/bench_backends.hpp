#pragma once
// What the Google Benchmark suites that time both backends share: the backend argument, the OpenCL
// device (chosen once per process, by $PHYSARUM_DEVICE or the default rule), and spot.obj at a
// resolution, skipping the benchmark with a message when the shared meshes are absent.
#include "bench/bench_support.hpp"
#include "opencl/runtime/compute_context.hpp"

#include <benchmark/benchmark.h>

namespace physarum::bench {

enum Backend { kReference = 0, kOpenCL = 1 };

inline const opencl::ComputeContext& compute() {
  static const opencl::ComputeContext c = opencl::make_compute_context("");
  return c;
}

// The benchmarks' resolution argument, in tenths of a millimetre, in metres.
inline double tenths_of_mm(long tenths) { return static_cast<double>(tenths) / 10000.0; }

// spot.obj scaled to 4 m^2 and refined to `max_circumradius_tenth_mm` tenths of a millimetre; nullptr
// (and the benchmark skipped) when it is absent.
inline const SurfaceDomain* spot_or_skip(benchmark::State& state, long max_circumradius_tenth_mm) {
  const SurfaceDomain* domain = scaled_domain("spot.obj", tenths_of_mm(max_circumradius_tenth_mm));
  if (!domain) state.SkipWithError("spot.obj not found under PHYSARUM_SHARED_MESHES (the shared/ folder is absent)");
  return domain;
}

}  // namespace physarum::bench
