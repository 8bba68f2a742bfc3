// The map tools (issue 20) at the size of the output benchmarks: spot.obj scaled to 4 m^2 and
// refined to ~50k and ~1.07M intrinsic faces (max circumradius 10 and 2.2 mm). Targets (issue 20):
// a Laplace solve on ~10^6 faces in <= 2 s.
//   BM_LaplaceSolve     two regions (spot's head and tail, half-spaces) held at 0 and 1: the reduced
//                       system's assembly, sparse Cholesky factorization and solve; second argument
//                       0: METIS orders the system in every call, 1: the surface's Laplacian ordering
//                       is computed once (ordering_s, as a scene's map tools share it:
//                       common/map_tools/surface_solvers.hpp) and each call restricts it
//   BM_DiffusionFactor  factoring M + h L (once per step size; shared by any number of steps)
//   BM_DiffusionStep    one backward-Euler step with the factor reused (a solve)
//   BM_Gradient         the normalised FE gradient of a map on every face
//   BM_Elevation        the elevation proxy of spot's INPUT mesh (5.9k faces; one implicit step)
// The triangulation is built once per process (bench_support.hpp) and not timed.
#include "bench/map_bench_support.hpp"
#include "common/map_tools/elevation_proxy.hpp"
#include "common/map_tools/laplace_interpolation.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/map_tools/surface_diffusion.hpp"
#include "common/map_tools/surface_gradient.hpp"
#include "common/map_tools/surface_solvers.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <optional>
#include <vector>

namespace physarum::bench {
namespace {


// A smooth map with some structure: x of each intrinsic vertex's input location.
IntrinsicVertexData<double> x_coordinate(const PreparedSurface& s) {
  IntrinsicVertexData<double> x(static_cast<size_t>(s.domain.vertex_count));
  for (int v = 0; v < s.domain.vertex_count; ++v) {
    const SurfacePoint& l = s.domain.vertex_location[v];
    const auto& t = s.input.triangles[static_cast<size_t>(l.face)];
    x[v] = l.barycentric[0] * s.input.positions[t[0]].x() + l.barycentric[1] * s.input.positions[t[1]].x() +
           l.barycentric[2] * s.input.positions[t[2]].x();
  }
  return x;
}

void BM_LaplaceSolve(benchmark::State& state) {
  const PreparedSurface* s = spot_surface(state).surface;
  if (!s) return;
  const IntrinsicVertexData<double> x = x_coordinate(*s);
  double low = 1e300, high = -1e300;
  for (const double v : x) low = std::min(low, v), high = std::max(high, v);
  std::vector<DirichletRegion> regions(2);
  regions[0] = {"head", {}, 0.0};
  regions[1] = {"tail", {}, 1.0};
  for (int v = 0; v < s->domain.vertex_count; ++v) {
    if (x[v] < low + 0.1 * (high - low)) regions[0].vertices.push_back(v);
    if (x[v] > high - 0.1 * (high - low)) regions[1].vertices.push_back(v);
  }
  std::optional<std::vector<int>> ordering;
  if (state.range(1) == 1) {
    const auto start = std::chrono::steady_clock::now();
    ordering = laplacian_fill_reducing_ordering(s->domain);
    state.counters["ordering_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  for (auto _ : state) benchmark::DoNotOptimize(laplace_interpolation(s->domain, regions, "bench", ordering ? &*ordering : nullptr));
  state.counters["intrinsic_faces"] = s->domain.face_count;
  state.counters["held_vertices"] = static_cast<double>(regions[0].vertices.size() + regions[1].vertices.size());
}

void BM_DiffusionFactor(benchmark::State& state) {
  const PreparedSurface* s = spot_surface(state).surface;
  if (!s) return;
  for (auto _ : state) {
    const BackwardEulerDiffusion diffusion(s->domain, 1e-4);
    benchmark::DoNotOptimize(&diffusion);
  }
  state.counters["intrinsic_faces"] = s->domain.face_count;
}

void BM_DiffusionStep(benchmark::State& state) {
  const PreparedSurface* s = spot_surface(state).surface;
  if (!s) return;
  const BackwardEulerDiffusion diffusion(s->domain, 1e-4);
  const IntrinsicVertexData<double> x = x_coordinate(*s);
  for (auto _ : state) benchmark::DoNotOptimize(diffusion.step(x));
  state.counters["intrinsic_faces"] = s->domain.face_count;
}

void BM_Gradient(benchmark::State& state) {
  const PreparedSurface* s = spot_surface(state).surface;
  if (!s) return;
  const IntrinsicVertexData<double> x = x_coordinate(*s);
  for (auto _ : state) benchmark::DoNotOptimize(gradient_vector_map(s->domain, x, true));
  state.counters["intrinsic_faces"] = s->domain.face_count;
}

void BM_Elevation(benchmark::State& state) {
  const PreparedSurface* s = spot_surface(state).surface;
  if (!s) return;
  for (auto _ : state) benchmark::DoNotOptimize(elevation_proxy(s->input, 0.005, 1, "bench"));
  state.counters["input_faces"] = s->input.triangle_count();
}

BENCHMARK(BM_LaplaceSolve)->Args({100, 0})->Args({100, 1})->Args({22, 0})->Args({22, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DiffusionFactor)->Arg(100)->Arg(22)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DiffusionStep)->Arg(100)->Arg(22)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Gradient)->Arg(100)->Arg(22)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Elevation)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace physarum::bench
