// Evaluating a scene's named maps on a large triangulation (common/maps/map_evaluation.hpp): spot.obj
// scaled to 4 m^2 and refined to ~50k and ~1.07M intrinsic faces (max circumradius 10 and 2.2 mm),
// the sizes of the output benchmarks.
//   BM_MapsProcedural  a ramp, a sphere region with falloff, a box, range/product/max arithmetic
//                      and a direction (vector map, one per face): per-element work only
//   BM_MapsPly         a per-vertex PLY property on the input mesh (read and interpolated) and a
//                      per-face PLY vector (read, located under each intrinsic face's centroid
//                      through the input-face overlap lists, projected into the face)
// The triangulation is built once per process (bench_support.hpp) and not timed; the PLY file is
// written once per benchmark, its reading is timed.
#include "bench/map_bench_support.hpp"
#include "common/maps/map_definition.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/output/ply_writer.hpp"
#include "common/setup/scene_surface.hpp"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <unistd.h>

namespace physarum::bench {
namespace {


void BM_MapsProcedural(benchmark::State& state) {
  const PreparedSurface* surface = spot_surface(state).surface;
  if (!surface) return;
  const MapSet maps = parse_maps(procedural_maps(), ".", "bench");
  for (auto _ : state) benchmark::DoNotOptimize(evaluate_maps(maps, *surface, "bench"));
  state.counters["intrinsic_faces"] = surface->domain.face_count;
  state.counters["intrinsic_vertices"] = surface->domain.vertex_count;
}

void BM_MapsPly(benchmark::State& state) {
  const PreparedSurface* surface = spot_surface(state).surface;
  if (!surface) return;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("physarum_bench_maps_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const InputMesh& input = surface->input;
  InputVertexData<double> weight(static_cast<size_t>(input.vertex_count()));
  for (int v = 0; v < input.vertex_count(); ++v) weight[v] = input.positions[static_cast<size_t>(v)].x();
  std::vector<double> x(input.triangles.size(), 1.0), y(input.triangles.size(), 0.5), z(input.triangles.size(), 0.0);
  write_fields_ply((dir / "maps.ply").string(), input, {PlyField{"weight", weight}},
                   {PlyFaceField{"flow_x", x}, PlyFaceField{"flow_y", y}, PlyFaceField{"flow_z", z}}, {}, "bench");
  const MapSet maps = parse_maps(nlohmann::json::parse(R"({
        "weight": {"ply": "maps.ply", "property": "weight"},
        "flow": {"ply": "maps.ply", "face_property": "flow"}
      })"),
                                 dir.string(), "bench");
  for (auto _ : state) benchmark::DoNotOptimize(evaluate_maps(maps, *surface, "bench"));
  state.counters["intrinsic_faces"] = surface->domain.face_count;
  std::filesystem::remove_all(dir);
}

BENCHMARK(BM_MapsProcedural)->Arg(100)->Arg(22)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapsPly)->Arg(100)->Arg(22)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace physarum::bench
