// Intrinsic triangulation preprocessing: Delaunay flips and Delaunay refinement on the shared
// meshes, at the refinement scale of the known-answer tests (max circumradius 0.5 % of the
// bounding-box diagonal). Reference timings from geometry-central on this kind of machine: bunny
// 0.25 s, bunny with a 25 degree min angle 0.42 s, spot 0.65 s. Loading the mesh is not timed.
#include "common/mesh/input_mesh.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <string>

namespace physarum {
namespace {

// Loads a shared mesh once per process; nullptr when the shared folder is absent.
const InputMesh* shared_mesh(const std::string& name) {
  static std::map<std::string, InputMesh> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  const std::filesystem::path path = std::filesystem::path(PHYSARUM_SHARED_MESHES) / name;
  if (!std::filesystem::exists(path)) return nullptr;
  return &cache.emplace(name, load_mesh(path.string())).first->second;
}

void BM_FlipToDelaunay(benchmark::State& state, const char* name) {
  const InputMesh* mesh = shared_mesh(name);
  if (!mesh) {
    state.SkipWithError((std::string("shared mesh ") + name + " not found under " + PHYSARUM_SHARED_MESHES).c_str());
    return;
  }
  size_t flips = 0;
  int vertices = 0;
  for (auto _ : state) {
    IntrinsicTriangulation tri(*mesh);
    flips = tri.flip_to_delaunay();
    vertices = tri.vertex_count();
    benchmark::DoNotOptimize(flips);
  }
  state.counters["flips"] = static_cast<double>(flips);
  state.counters["vertices_out"] = vertices;
}

void BM_Refine(benchmark::State& state, const char* name, double min_angle_deg) {
  const InputMesh* mesh = shared_mesh(name);
  if (!mesh) {
    state.SkipWithError((std::string("shared mesh ") + name + " not found under " + PHYSARUM_SHARED_MESHES).c_str());
    return;
  }
  RefinementOptions options;
  options.max_circumradius = 0.005 * bounding_box_diagonal(*mesh);
  options.min_angle_deg = min_angle_deg;
  int vertices = 0;
  size_t insertions = 0;
  for (auto _ : state) {
    // Construction included: it is part of what a user waits for (geometry-central's timing too).
    IntrinsicTriangulation tri(*mesh);
    const RefinementResult result = tri.refine(options);
    vertices = tri.vertex_count();
    insertions = result.insertions();
    benchmark::DoNotOptimize(vertices);
  }
  state.counters["vertices_out"] = vertices;
  state.counters["insertions"] = static_cast<double>(insertions);
}

BENCHMARK_CAPTURE(BM_FlipToDelaunay, spot, "spot.obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FlipToDelaunay, bunny, "stanford-bunny.obj")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Refine, spot, "spot.obj", 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Refine, bunny, "stanford-bunny.obj", 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Refine, bunny_min_angle_25, "stanford-bunny.obj", 25.0)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace physarum
