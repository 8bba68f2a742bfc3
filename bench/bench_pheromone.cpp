// The pheromone step alone (Eq. 6 forward Euler, Eq. 7 backward Euler), both backends side by side,
// on spot.obj scaled to 4 m^2 from 6k to 1.3M intrinsic faces (and the backward step on the built-in
// square too: 1,089 vertices, the 10^3 end of the implicit solve's range, which spot cannot reach); the OpenCL field numbered as a
// simulation numbers it (opencl::in_device_vertex_order). Counters: vertices per second, the
// forward-Euler sub-steps per step (finer meshes need more for stability), and for the OpenCL forward
// step the bytes per second its sub-step matrix and fields move, to set against the machine's
// bandwidth (`physarum bench` prints both as a roofline). The backward step four ways: the reference,
// the OpenCL field as it runs here (a CPU device: the host's float Cholesky factor,
// opencl/host_cholesky_solve.hpp, run in the device's queue, opencl/runtime/queued_host_task.hpp), the same
// factor on the field mapped by the host (a GPU's path for small fields), and the OpenCL field with
// device conjugate gradients (a GPU's path for large ones).
#include "bench/bench_backends.hpp"
#include "common/model/vertex_parameters.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/face_records.hpp"
#include "opencl/diffusion_decay.hpp"
#include "opencl/host_cholesky_solve.hpp"
#include "common/model/pheromone_operators.hpp"
#include "reference/diffusion_decay.hpp"

#include <benchmark/benchmark.h>

namespace physarum::bench {
namespace {

// Backend argument 2: the OpenCL field with its backward-Euler system solved by conjugate gradients
// on the device even where the automatic choice is the host's Cholesky factor (a CPU device).
constexpr int kOpenCLWithDeviceCG = 2;
// Backend argument 3: the OpenCL field with the host factor solving on the field mapped by the host
// (one wait per step) even where the device could run it in its queue (opencl/runtime/queued_host_task.hpp).
constexpr int kOpenCLMapped = 3;
// Mesh argument 3: spot.obj, or the built-in square (32 x 32 cells: scaled to 4 m^2 its triangles'
// circumradius is 4.4 cm, so a 10 cm bound leaves its 1,089 vertices as they are).
constexpr int kSpot = 0;
constexpr int kSquare = 1;

void BM_PheromoneStep(benchmark::State& state) {
  const bool device_cg = state.range(0) == kOpenCLWithDeviceCG;
  const bool mapped = state.range(0) == kOpenCLMapped;
  const auto backend = device_cg || mapped ? kOpenCL : static_cast<Backend>(state.range(0));
  const auto integrator = state.range(1) == 0 ? Integrator::Forward : Integrator::Backward;
  const bool square = state.range(3) == kSquare;
  const int steps_per_sync = static_cast<int>(state.range(4));
  const SurfaceDomain* domain =
      square ? scaled_domain("shape:square", tenths_of_mm(state.range(2))) : spot_or_skip(state, state.range(2));
  if (!domain) return;
  const Scene scene = bench_scene(0);
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, domain->vertex_count);
  int sub_steps = 1;
  double bytes_per_sub_step = 0.0;
  if (backend == kOpenCL) {
    const SurfaceDomain device_domain = opencl::in_device_vertex_order(*domain);
    opencl::OpenCLDiffusionDecayOptions options;
    if (device_cg) options.implicit_solver = opencl::ImplicitSolver::DeviceConjugateGradients;
    if (mapped) options.host_solve_in_queue = false;
    opencl::OpenCLDiffusionDecay field(compute(), device_domain, params, integrator, scene.time_step, options);
    field.fill(1.0);
    for (auto _ : state) {
      for (int s = 0; s < steps_per_sync; ++s) field.step();
      compute().queue.finish();
    }
    sub_steps = field.sub_steps();
    bytes_per_sub_step = field.forward_bytes_per_sub_step();
  } else {
    ReferenceDiffusionDecay model(*domain, params, integrator, scene.time_step);
    IntrinsicVertexData<double> u(static_cast<size_t>(domain->vertex_count), 1.0);
    for (auto _ : state)
      for (int s = 0; s < steps_per_sync; ++s) model.step(u);
    sub_steps = model.sub_steps();
  }
  state.SetLabel(device_cg ? "opencl, device CG" : mapped ? "opencl, mapped host solve" : backend == kOpenCL ? "opencl" : "reference");
  state.counters["vertices_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * steps_per_sync * domain->vertex_count, benchmark::Counter::kIsRate);
  state.counters["vertices"] = domain->vertex_count;
  state.counters["ms_per_step"] = benchmark::Counter(1e-3 * steps_per_sync, benchmark::Counter::kIsIterationInvariantRate |
                                                                               benchmark::Counter::kInvert);
  if (integrator == Integrator::Forward) state.counters["sub_steps"] = sub_steps;
  if (bytes_per_sub_step > 0.0)
    state.counters["bytes_per_s"] = benchmark::Counter(
        bytes_per_sub_step * sub_steps * steps_per_sync * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Args: {backend, integrator (0 forward, 1 backward), max circumradius in tenths of a mm, mesh, steps
// per sync}. Backward Euler four ways (the device-CG and mapped-host-solve variants too), from 1k
// (the square) to 1.3M vertices. Steps per sync 1: each step waits for the device (its latency);
// 64: as `physarum run` issues them, many steps between waits (it waits only for a statistics row,
// a frame or a checkpoint), so ms_per_step is what a run pays per step (its throughput).
BENCHMARK(BM_PheromoneStep)
    ->ArgsProduct({{kReference, kOpenCL}, {0}, {400, 150, 50, 25, 20}, {kSpot}, {1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_PheromoneStep)
    ->ArgsProduct({{kReference, kOpenCL, kOpenCLWithDeviceCG, kOpenCLMapped}, {1}, {1000}, {kSquare}, {1, 64}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_PheromoneStep)
    ->ArgsProduct({{kReference, kOpenCL, kOpenCLWithDeviceCG, kOpenCLMapped}, {1}, {1000, 400, 150, 100, 50, 20, 14}, {kSpot}, {1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_PheromoneStep)
    ->ArgsProduct({{kReference, kOpenCL}, {1}, {1000, 400, 150}, {kSpot}, {64}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The backward-Euler system's host solve alone (opencl/host_cholesky_solve.hpp), one right-hand side:
// the simplicial L D L^T with our sweeps against the supernodal L L^T (common/numerics/supernodal_solve.hpp),
// each in float (the pheromone) and double (the reaction-diffusion IMEX step). Args: {supernodal,
// double, max circumradius in tenths of a mm}. This is what sets kMinSupernodalRows.
void BM_HostCholeskySolve(benchmark::State& state) {
  const bool supernodal = state.range(0) != 0;
  const auto precision = state.range(1) != 0 ? opencl::FactorPrecision::Double : opencl::FactorPrecision::Single;
  const SurfaceDomain* domain = spot_or_skip(state, state.range(2));
  if (!domain) return;
  const Scene scene = bench_scene(0);
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, domain->vertex_count);
  const BackwardEulerSystem system = backward_euler_system(domain->laplacian, domain->vertex_mass,
                                                           params[Param::diffuse_rate], params[Param::decay_rate],
                                                           scene.time_step);
  const int n = domain->vertex_count;
  opencl::HostCholeskySolve solve(system.system, precision, "benchmark", opencl::kMaxRowCopyBytes,
                                  supernodal ? 0 : n + 1);
  std::vector<float> u(static_cast<size_t>(n), 1.0f);
  for (auto _ : state) {
    solve.solve(u.data(), u.data());
    benchmark::DoNotOptimize(u.data());
  }
  state.SetLabel(std::string(supernodal ? "supernodal" : "simplicial") +
                 (precision == opencl::FactorPrecision::Double ? ", double" : ", float"));
  state.counters["vertices"] = n;
}
BENCHMARK(BM_HostCholeskySolve)
    ->ArgsProduct({{0, 1}, {0, 1}, {400, 150, 100, 70, 50, 20}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace physarum::bench
