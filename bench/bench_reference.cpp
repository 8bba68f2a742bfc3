// Throughput of the serial reference: agent-steps per second of the full step (sense + steer, move
// + deposit, turnover, pheromone) on spot.obj scaled to 4 m^2, at two intrinsic resolutions
// (max circumradius 0.04 m and 0.015 m) and 1e4, 1e5, 1e6 agents. The domain is built once per
// resolution and not timed; each benchmark times steps after a short warm-up, so pheromone is
// present and agents sense and turn as in a real run. Skipped when the shared meshes are absent.
#include "common/input_mesh.hpp"
#include "common/intrinsic_triangulation.hpp"
#include "common/mesh_loading.hpp"
#include "common/scene.hpp"
#include "common/surface_domain.hpp"
#include "reference/simulation.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <string>

namespace physarum {
namespace {

// The spot domain at a given max circumradius (m, after scaling to 4 m^2), built once; nullptr
// when the shared folder is absent.
const SurfaceDomain* spot_domain(double max_circumradius) {
  static std::map<double, std::unique_ptr<SurfaceDomain>> cache;
  auto it = cache.find(max_circumradius);
  if (it != cache.end()) return it->second.get();
  const std::filesystem::path path = std::filesystem::path(PHYSARUM_SHARED_MESHES) / "spot.obj";
  if (!std::filesystem::exists(path)) return nullptr;
  InputMesh mesh = load_mesh(path.string());
  const double area = compute_statistics(mesh).area;
  for (Eigen::Vector3d& p : mesh.positions) p *= std::sqrt(4.0 / area);
  IntrinsicTriangulation triangulation(mesh);
  triangulation.flip_to_delaunay();
  RefinementOptions refinement;
  refinement.max_circumradius = max_circumradius;
  triangulation.refine(refinement);
  auto domain = std::make_unique<SurfaceDomain>(build_surface_domain(triangulation.snapshot()));
  return cache.emplace(max_circumradius, std::move(domain)).first->second.get();
}

Scene bench_scene(int agents) {
  Scene s;
  s.agents = agents;
  s.time_step = 0.01;
  s.sensor_distance = 0.05;
  s.sensor_angle = 22.5 * std::numbers::pi / 180.0;
  s.move_rate = 0.5;
  s.turn_rate = std::numbers::pi;
  s.turn_frequency = 20.0;
  s.deposit_rate = 1.0;
  s.decay_rate = 1.0;
  s.diffuse_rate = 0.0002;
  s.mean_lifetime = 1.0;
  s.activation_time = 0.2;
  s.seed = 1;
  return s;
}

void BM_ReferenceStep(benchmark::State& state) {
  const double max_circumradius = state.range(0) / 1000.0;
  const int agents = static_cast<int>(state.range(1));
  const SurfaceDomain* domain = spot_domain(max_circumradius);
  if (!domain) {
    state.SkipWithError("spot.obj not found under PHYSARUM_SHARED_MESHES (the shared/ folder is absent)");
    return;
  }
  ReferenceSimulation sim(*domain, bench_scene(agents));
  sim.run(5);  // warm-up: some pheromone to sense
  const long long crossings_before = sim.counters().face_crossings;
  for (auto _ : state) sim.step();
  state.SetItemsProcessed(state.iterations() * agents);
  state.counters["agent_steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * agents, benchmark::Counter::kIsRate);
  state.counters["face_crossings_per_agent_step"] =
      static_cast<double>(sim.counters().face_crossings - crossings_before) /
      (static_cast<double>(state.iterations()) * agents);
  state.counters["intrinsic_vertices"] = domain->vertex_count;
}

// Args: {max circumradius in mm, agents}.
BENCHMARK(BM_ReferenceStep)
    ->ArgsProduct({{40, 15}, {10'000, 100'000, 1'000'000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace physarum
