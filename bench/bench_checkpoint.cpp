// The cost of one checkpoint (`physarum run --checkpoint-every`), both backends: saving the whole
// state (a device backend reads its buffers back), encoding it with its checksum, and writing the
// file atomically, on the default scene's surface (tools/scenes/default.json: the sphere at 4 m^2,
// max circumradius 2 cm) with 10k and 100k agents. Counter: the checkpoint's bytes. What the
// interval costs is this time once per interval; run.json's "checkpoints" reports it for a real run.
#include "bench/bench_backends.hpp"
#include "common/setup/agent_inputs.hpp"
#include "common/base/atomic_write.hpp"
#include "common/run/checkpoint.hpp"
#include "common/scene/default_scene.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/simulation/simulation_state.hpp"
#include "opencl/agent_simulation.hpp"
#include "reference/agent_simulation.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <unistd.h>

namespace physarum::bench {
namespace {

const SurfaceDomain& default_sphere() {
  static const PreparedSurface surface = [] {
    SurfaceSpec spec;
    spec.mesh = "shape:sphere";
    spec.scale_to_area = 4.0;
    spec.max_circumradius = 0.02;
    return prepare_surface(spec);
  }();
  return surface.domain;
}

void BM_Checkpoint(benchmark::State& state) {
  const auto backend = static_cast<Backend>(state.range(0));
  const Scene scene = default_scene_parameters(static_cast<int>(state.range(1)));
  std::unique_ptr<SimulationBackend> sim;
  if (backend == kOpenCL)
    sim = std::make_unique<opencl::OpenCLAgentSimulation>(compute(), default_sphere(), constant_parameters(scene, default_sphere()), simulation_settings(scene));
  else
    sim = std::make_unique<ReferenceAgentSimulation>(default_sphere(), constant_parameters(scene, default_sphere()), simulation_settings(scene));
  sim->run(10);
  sim->finish();
  CheckpointHeader header;
  header.build_id = checkpoint_build_id();
  header.backend = sim->backend_name();
  header.device = sim->device_name();
  header.step = sim->steps_taken();
  const std::string path =
      (std::filesystem::temp_directory_path() / ("physarum_bench_checkpoint_" + std::to_string(::getpid()) + ".bin")).string();
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string encoded = checkpoint_bytes(header, sim->save_state());
    write_text_file_atomically(path, encoded);
    bytes = encoded.size();
  }
  std::filesystem::remove(path);
  state.SetLabel(sim->backend_name());
  state.counters["bytes"] = static_cast<double>(bytes);
  state.counters["vertices"] = default_sphere().vertex_count;
}

// Args: {backend, agents}.
BENCHMARK(BM_Checkpoint)->ArgsProduct({{kReference, kOpenCL}, {10000, 100000}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace physarum::bench
