// The full-resolution outputs of a run at the sizes the issue targets: spot.obj scaled to 4 m^2 and
// refined to ~1.07M intrinsic faces (max circumradius 2.2 mm), and to ~50k (10 mm) for scaling.
//   BM_FullResolutionExport  the full-resolution mesh built from the triangulation and written as
//                            fields_full.ply (target: <= 1 s at 10^6 faces)
//   BM_TextureBake           locating every texel of a W x W texture on the triangulation (the
//                            per-input-face overlap lists included) and baking one field with
//                            16 px seam padding (target: <= 2 s for 2048^2 at 10^6 faces)
//   BM_TextureBakeField      baking one more field (or frame) from locations made once
// The triangulation is built once per process (bench_support.hpp) and not timed.
#include "bench/bench_support.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/output/ply_writer.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/output/texture_bake.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <unistd.h>

namespace physarum::bench {
namespace {

// spot.obj at `max_circumradius_tenth_mm` tenths of a millimetre; nullptr (benchmark skipped) when
// the shared meshes are absent.
const PreparedSurface* spot_surface(benchmark::State& state, long max_circumradius_tenth_mm) {
  const std::string spec = mesh_spec("spot.obj");
  if (spec.empty()) {
    state.SkipWithError("spot.obj not found under PHYSARUM_SHARED_MESHES (the shared/ folder is absent)");
    return nullptr;
  }
  return &surfaces().get(bench_surface(spec, static_cast<double>(max_circumradius_tenth_mm) / 10000.0));
}

// A smooth field with detail at every scale the triangulation resolves.
IntrinsicVertexData<double> wavy_field(const FullResolutionMesh& full) {
  IntrinsicVertexData<double> field(full.mesh.positions.size());
  for (size_t v = 0; v < field.size(); ++v) {
    const Eigen::Vector3d& p = full.mesh.positions[v];
    field[v] = 1.0 + std::sin(40.0 * p.x()) * std::cos(37.0 * p.y()) + 0.5 * p.z();
  }
  return field;
}

void BM_FullResolutionExport(benchmark::State& state) {
  const PreparedSurface* surface = spot_surface(state, state.range(0));
  if (!surface) return;
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("physarum_bench_fields_full_" + std::to_string(::getpid()) + ".ply");
  const IntrinsicVertexData<double> field = wavy_field(build_full_resolution_mesh(surface->input, surface->domain));
  for (auto _ : state) {
    const FullResolutionMesh full = build_full_resolution_mesh(surface->input, surface->domain);
    const InputVertexData<double> values = full.vertex_values(field);
    write_fields_ply(path.string(), full.mesh, {PlyField{"pheromone", values}}, FieldColoring{}, "pheromone per vertex");
  }
  state.counters["intrinsic_faces"] = surface->domain.face_count;
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  std::filesystem::remove(path);
}

void BM_TextureBake(benchmark::State& state) {
  const PreparedSurface* surface = spot_surface(state, state.range(0));
  if (!surface) return;
  const int size = static_cast<int>(state.range(1));
  const IntrinsicVertexData<double> field = wavy_field(build_full_resolution_mesh(surface->input, surface->domain));
  size_t covered = 0, searched = 0;
  for (auto _ : state) {
    const TexelLocations locations = locate_texels(surface->input, surface->domain, size, size);
    const BakedTexture texture = bake_fields(locations, surface->domain, {BakeField{"pheromone", field}});
    benchmark::DoNotOptimize(texture.values.data());
    covered = locations.covered_texels;
    searched = locations.nearest_search_texels;
  }
  state.counters["intrinsic_faces"] = surface->domain.face_count;
  state.counters["covered_texels"] = static_cast<double>(covered);
  state.counters["nearest_searches"] = static_cast<double>(searched);
}

void BM_TextureBakeField(benchmark::State& state) {
  const PreparedSurface* surface = spot_surface(state, state.range(0));
  if (!surface) return;
  const int size = static_cast<int>(state.range(1));
  const IntrinsicVertexData<double> field = wavy_field(build_full_resolution_mesh(surface->input, surface->domain));
  const TexelLocations locations = locate_texels(surface->input, surface->domain, size, size);
  for (auto _ : state) {
    const BakedTexture texture = bake_fields(locations, surface->domain, {BakeField{"pheromone", field}});
    benchmark::DoNotOptimize(texture.values.data());
  }
  state.counters["intrinsic_faces"] = surface->domain.face_count;
}

// Args: {max circumradius in tenths of a mm, texture size}.
BENCHMARK(BM_FullResolutionExport)->Arg(100)->Arg(22)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TextureBake)
    ->ArgsProduct({{100, 22}, {512, 2048}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_TextureBakeField)->Args({22, 2048})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace physarum::bench
