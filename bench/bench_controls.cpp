// The cost of the controls of Sec. 3.3 (common/model/simulation_controls.hpp): the full step on spot.obj
// (4 m^2, 15 mm, ~24k faces) with 100k agents, on both backends, once with a parameter map (sensor
// distance ramped along the body), a read-stimulus, a write-stimulus and a directional bias (n = 2)
// and once without any control on the same parameters. Agent steps per second; the ratio with /
// without is the overhead of the controls (target >= 0.7x; bench/README.md).
#include "bench/bench_backends.hpp"
#include "common/setup/agent_inputs.hpp"
#include "common/model/simulation_controls.hpp"
#include "common/setup/workload.hpp"
#include "opencl/agent_simulation.hpp"
#include "reference/agent_simulation.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

namespace physarum::bench {
namespace {

// The controls and the sensor-distance map, from the vertex locations on the input mesh (a ramp along
// the input's x coordinate through the barycentric location, and a disk-like stimulus pattern).
struct ControlledScene {
  VertexParameters params;
  SimulationControls controls;
};

// Which controls a row switches on (a bit mask, the benchmark's second argument).
enum ControlBits { kMap = 1, kReadStimulus = 2, kWriteStimulus = 4, kBias = 8, kAll = 15 };

ControlledScene controlled_scene(const SurfaceDomain& domain, const Scene& scene, long bits) {
  ControlledScene c{VertexParameters::constant(scene.agent_model().parameters, domain.vertex_count), {}};
  const size_t n = static_cast<size_t>(domain.vertex_count);
  IntrinsicVertexData<double> read_stimulus(n, 0.0), write_rate(n, 0.0);
  VertexParameters mapped = c.params;
  DirectionalBias bias;
  bias.symmetry = 2;
  bias.strength.assign(n, 1.0);
  bias.direction.assign(static_cast<size_t>(domain.face_count), {1.0, 0.0});
  for (size_t i = 0; i < n; ++i) {
    // A smooth pseudo-position in 0..1 from the vertex's input face and barycentric coordinates:
    // enough for the costs (memory reads, interpolation), which do not depend on the map's shape.
    const SurfacePoint& p = domain.vertex_location[i];
    const double t = std::fmod(0.37 * p.face + p.barycentric[1], 1.0);
    mapped[Param::sensor_distance][i] *= 0.5 + t;
    read_stimulus[i] = t > 0.8 ? 1.0 : 0.0;
    write_rate[i] = t < 0.1 ? 0.5 : 0.0;
  }
  if (bits & kMap) c.params = mapped;
  if (bits & kReadStimulus) c.controls.read_stimulus = read_stimulus;
  if (bits & kWriteStimulus) c.controls.write_rate = write_rate;
  if (bits & kBias) c.controls.bias = bias;
  return c;
}

void BM_ControlsStep(benchmark::State& state) {
  const auto backend = static_cast<Backend>(state.range(0));
  const long bits = state.range(1);
  const int agents = 100'000;
  const SurfaceDomain* domain = spot_or_skip(state, 150);
  if (!domain) return;
  const Scene scene = bench_scene(agents);
  const ControlledScene c = controlled_scene(*domain, scene, bits);
  std::unique_ptr<SimulationBackend> sim;
  if (backend == kOpenCL)
    sim = std::make_unique<opencl::OpenCLAgentSimulation>(compute(), *domain, c.params, c.controls,
                                                     simulation_settings(scene));
  else
    sim = std::make_unique<ReferenceAgentSimulation>(*domain, c.params, c.controls, simulation_settings(scene));
  sim->run(5);
  sim->finish();
  for (auto _ : state) {
    sim->step();
    sim->finish();
  }
  const char* what = bits == 0 ? " none" : (bits == kAll ? " all controls" : " some controls");
  state.SetLabel(std::string(backend == kOpenCL ? "opencl" : "reference") + what);
  state.counters["agent_steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * agents, benchmark::Counter::kIsRate);
}

// Args: {backend, ControlBits}: none, all, then each alone (where the cost comes from).
BENCHMARK(BM_ControlsStep)
    ->ArgsProduct({{kReference, kOpenCL}, {0, kAll, kMap, kReadStimulus, kWriteStimulus, kBias}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace physarum::bench
