// Throughput of the full simulation step (agents + pheromone) on both backends, side by side in one
// run so their ratio is meaningful on a shared machine: spot.obj scaled to 4 m^2 at intrinsic
// resolutions from 6k to 800k faces, 1e4 .. 1e6 agents. The domain is built once and
// not timed; each benchmark first takes a few steps so there is pheromone to sense. Counters: agent
// steps per second, face crossings (movement + sensors) per agent step and per second.
#include "bench/bench_backends.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "api/backend_factory.hpp"

#include <benchmark/benchmark.h>

#include <memory>

namespace physarum::bench {
namespace {

void BM_SimulationStep(benchmark::State& state) {
  const auto backend = static_cast<Backend>(state.range(0));
  const int agents = static_cast<int>(state.range(2));
  const SurfaceDomain* domain = spot_or_skip(state, state.range(1));
  if (!domain) return;
  const Workload workload =
      bench_workload("spot.obj", mesh_spec("spot.obj"), tenths_of_mm(state.range(1)),
                     bench_scene(agents), backend == kOpenCL ? BackendChoice::OpenCL : BackendChoice::Reference);
  const std::unique_ptr<SimulationBackend> sim =
      make_backend(workload, surfaces(), backend == kOpenCL ? &compute() : nullptr);
  sim->run(5);
  sim->finish();
  const SimulationCounters before = sim->counters();
  for (auto _ : state) {
    sim->step();
    sim->finish();
  }
  const SimulationCounters after = sim->counters();
  const double agent_steps = static_cast<double>(state.iterations()) * agents;
  const double crossings = static_cast<double>(after.face_crossings + after.sensor_face_crossings -
                                               before.face_crossings - before.sensor_face_crossings);
  state.SetLabel(backend == kOpenCL ? "opencl" : "reference");
  state.counters["agent_steps_per_s"] = benchmark::Counter(agent_steps, benchmark::Counter::kIsRate);
  state.counters["crossings_per_s"] = benchmark::Counter(crossings, benchmark::Counter::kIsRate);
  state.counters["crossings_per_agent_step"] = crossings / agent_steps;
  state.counters["faces"] = domain->face_count;
}

// Args: {backend, max circumradius in tenths of a mm, agents}. 40 mm: 6k faces; 15 mm: 24k faces;
// 5 mm: ~200k faces (13 MB of face records, inside this machine's 32 MB cache); 2.5 mm: ~800k
// faces (51 MB, outside it).
BENCHMARK(BM_SimulationStep)
    ->ArgsProduct({{kReference, kOpenCL}, {400, 150}, {10'000, 100'000, 1'000'000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SimulationStep)
    ->ArgsProduct({{kReference, kOpenCL}, {50, 25}, {1'000'000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace physarum::bench
