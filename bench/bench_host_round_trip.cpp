// What it costs the host to work on a device field in place (opencl/runtime/mapped_buffer.hpp, the host
// implicit solves of opencl/host_cholesky_solve.hpp): one round trip of n floats through the queue,
// three ways, each ending with the queue drained as a step does:
//   0  a launch (an empty kernel standing in for the right-hand side), a blocking read, a blocking
//      write: the host solve's transfers before the fields were mapped;
//   1  a blocking map for reading and writing, every value touched, the unmap: what the host
//      solves do now;
//   2  clFinish alone: the floor, one wait for the runtime's threads.
// On a CPU device (PoCL) every variant's cost is mostly waits for the runtime's worker threads, so
// it grows with the machine's load; the map itself moves no data there.
#include "bench/bench_backends.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/runtime/mapped_buffer.hpp"

#include <benchmark/benchmark.h>

#include <vector>

namespace physarum::bench {
namespace {

void BM_FieldRoundTrip(benchmark::State& state) {
  const opencl::ComputeContext& c = compute();
  const size_t n = static_cast<size_t>(state.range(1));
  const opencl::DeviceBuffer field = opencl::allocate_written<cl_float>(c, "round-trip field", n);
  c.queue.enqueueFillBuffer(field.buffer, 1.0f, 0, n * sizeof(float));
  cl::Program program(c.context, "__kernel void touch(__global float* u) { (void)u; }", true);
  cl::Kernel touch(program, "touch");
  touch.setArg(0, field.buffer);
  std::vector<float> host(n);
  c.queue.finish();
  for (auto _ : state) {
    if (state.range(0) == 0) {
      c.queue.enqueueNDRangeKernel(touch, cl::NullRange, cl::NDRange(1));
      c.queue.enqueueReadBuffer(field.buffer, CL_TRUE, 0, n * sizeof(float), host.data());
      for (float& x : host) x += 1.0f;
      c.queue.enqueueWriteBuffer(field.buffer, CL_TRUE, 0, n * sizeof(float), host.data());
    } else if (state.range(0) == 1) {
      const opencl::MappedBuffer<float> u(c, field, CL_MAP_READ | CL_MAP_WRITE, 0, n);
      for (size_t i = 0; i < n; ++i) u[i] += 1.0f;
    }
    c.queue.finish();
  }
  state.SetLabel(state.range(0) == 0 ? "launch + read + write" : state.range(0) == 1 ? "map + unmap" : "finish only");
  state.counters["floats"] = static_cast<double>(n);
}
BENCHMARK(BM_FieldRoundTrip)
    ->ArgsProduct({{0, 1, 2}, {3000, 100000, 1000000}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

}  // namespace
}  // namespace physarum::bench
