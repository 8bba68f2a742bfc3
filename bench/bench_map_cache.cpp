// The map cache (common/setup/cached_map_evaluation.hpp) on the sizes of bench_maps.cpp: spot.obj scaled
// to 4 m^2 and refined to ~50k and ~1.07M intrinsic faces, with BM_MapsProcedural's seven maps.
//   BM_MapCacheKeys  the keys alone: the executable's and the triangulation's hashes, the JSON
//   BM_MapsFromCache a warm cache: keys, then every map read back and checked (what a second run
//                    pays instead of evaluating; compare BM_MapsProcedural, and for the map tools
//                    their own benchmarks)
// The entries live in a temporary folder, written once before timing.
#include "bench/map_bench_support.hpp"
#include "common/setup/cached_map_evaluation.hpp"
#include "common/maps/map_cache.hpp"
#include "common/maps/map_definition.hpp"
#include "common/setup/scene_surface.hpp"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <unistd.h>

namespace physarum::bench {
namespace {


void BM_MapCacheKeys(benchmark::State& state) {
  const SpotSurface f = spot_surface(state);
  if (!f.surface) return;
  const MapSet maps = parse_maps(procedural_maps(), ".", "bench");
  const MapSources sources{maps, procedural_maps(), ".", f.spec, "bench"};
  for (auto _ : state) benchmark::DoNotOptimize(map_cache_keys(sources, *f.surface));
  state.counters["intrinsic_faces"] = f.surface->domain.face_count;
}

void BM_MapsFromCache(benchmark::State& state) {
  const SpotSurface f = spot_surface(state);
  if (!f.surface) return;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("physarum_bench_map_cache_" + std::to_string(::getpid()));
  const MapCache cache(dir);
  const MapSet maps = parse_maps(procedural_maps(), ".", "bench");
  const MapSources sources{maps, procedural_maps(), ".", f.spec, "bench"};
  cached_evaluate_maps(sources, *f.surface, cache);  // fills the cache
  MapEvaluationReport report;
  for (auto _ : state) benchmark::DoNotOptimize(cached_evaluate_maps(sources, *f.surface, cache, &report));
  if (report.from_cache.size() != 7) state.SkipWithError("the cache did not serve every map");
  state.counters["intrinsic_faces"] = f.surface->domain.face_count;
  std::filesystem::remove_all(dir);
}

BENCHMARK(BM_MapCacheKeys)->Arg(100)->Arg(22)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapsFromCache)->Arg(100)->Arg(22)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace physarum::bench
