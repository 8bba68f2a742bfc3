// The pheromone step alone (Eq. 6 forward Euler, Eq. 7 backward Euler), both backends side by side,
// on spot.obj scaled to 4 m^2 from 6k to 850k intrinsic faces. Counters: vertices per second, the
// forward-Euler sub-steps per step (finer meshes need more for stability), and for forward Euler the
// bytes per second at ~104 bytes per vertex and sub-step (a CSR row of ~7 entries with its gathered
// values, two rates, u in and out), to set against the machine's bandwidth (`physarum bench`).
#include "bench/bench_backends.hpp"
#include "common/vertex_parameters.hpp"
#include "opencl/compute_context.hpp"
#include "opencl/pheromone.hpp"
#include "reference/pheromone.hpp"

#include <benchmark/benchmark.h>

namespace physarum::bench {
namespace {

void BM_PheromoneStep(benchmark::State& state) {
  const auto backend = static_cast<Backend>(state.range(0));
  const auto integrator = state.range(1) == 0 ? Integrator::ForwardEuler : Integrator::BackwardEuler;
  const SurfaceDomain* domain = spot_or_skip(state, state.range(2));
  if (!domain) return;
  const Scene scene = bench_scene(0);
  const VertexParameters params = VertexParameters::constant(scene, domain->vertex_count);
  int sub_steps = 1;
  if (backend == kOpenCL) {
    opencl::OpenCLPheromone field(compute(), *domain, params, integrator, scene.time_step);
    field.fill(1.0);
    for (auto _ : state) {
      field.step();
      compute().queue.finish();
    }
    sub_steps = field.sub_steps();
  } else {
    ReferencePheromone field(*domain, params, integrator, scene.time_step);
    field.fill(1.0);
    for (auto _ : state) field.step();
    sub_steps = field.sub_steps();
  }
  state.SetLabel(backend == kOpenCL ? "opencl" : "reference");
  state.counters["vertices_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * domain->vertex_count, benchmark::Counter::kIsRate);
  state.counters["vertices"] = domain->vertex_count;
  if (integrator == Integrator::ForwardEuler) {
    state.counters["sub_steps"] = sub_steps;
    state.counters["bytes_per_s"] = benchmark::Counter(
        104.0 * sub_steps * static_cast<double>(state.iterations()) * domain->vertex_count, benchmark::Counter::kIsRate);
  }
}

// Args: {backend, integrator (0 forward, 1 backward), max circumradius in tenths of a mm}.
BENCHMARK(BM_PheromoneStep)
    ->ArgsProduct({{kReference, kOpenCL}, {0, 1}, {400, 150, 50, 25}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace physarum::bench
