#pragma once
// What the map benchmarks share (bench_maps, bench_map_cache, bench_map_tools): spot.obj at the sizes
// of the output benchmarks, and the procedural maps whose evaluation and caching they time.
#include "bench/bench_support.hpp"
#include "common/setup/scene_surface.hpp"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

namespace physarum::bench {

// spot.obj scaled to 4 m^2 and refined to state.range(0) / 10^4 metres (100: ~50k faces, 22: ~1.07M).
struct SpotSurface {
  const PreparedSurface* surface = nullptr;  // null, with the benchmark skipped, without shared meshes
  SurfaceSpec spec;
};

inline SpotSurface spot_surface(benchmark::State& state) {
  SpotSurface s;
  const std::string mesh = mesh_spec("spot.obj");
  if (mesh.empty()) {
    state.SkipWithError("spot.obj not found under PHYSARUM_SHARED_MESHES (the shared/ folder is absent)");
    return s;
  }
  s.spec = bench_surface(mesh, static_cast<double>(state.range(0)) / 10000.0);
  s.surface = &surfaces().get(s.spec);
  return s;
}

// Seven maps of per-element work: a ramp, a sphere region with falloff, a box, range/product/max
// arithmetic and a direction (a vector map).
inline const nlohmann::json& procedural_maps() {
  static const nlohmann::json maps = nlohmann::json::parse(R"({
        "ramp": {"axis": "y"},
        "spot": {"sphere": {"center": [0.1, 0.3, 0.0], "radius": 0.2}, "falloff": 0.05},
        "box": {"box": {"min": [-0.2, -0.2, -0.2], "max": [0.2, 0.2, 0.2]}},
        "scale": {"map": "ramp", "range": [0.5, 1.5]},
        "scaled_spot": {"product": ["scale", "spot"]},
        "mix": {"max": ["scaled_spot", "box"]},
        "east": {"direction": [1.0, 0.0, 0.0]}
      })");
  return maps;
}

}  // namespace physarum::bench
