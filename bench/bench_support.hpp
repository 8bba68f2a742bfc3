#pragma once
// What the benchmark suites share: the surfaces they run on (built once per process through the
// shared surface loader, common/scene_surface.hpp, skipped with a message when the shared meshes
// are absent) and the model parameters of the agent benchmarks (common/workload.hpp).
#include "common/surface_domain.hpp"
#include "common/workload.hpp"

#include <filesystem>
#include <string>

namespace physarum::bench {

using physarum::bench_scene;

// The intrinsic domain of `mesh` (a shared mesh file name, or shape:NAME) scaled to 4 m^2 and
// refined to `max_circumradius` metres; nullptr when a shared mesh is absent.
inline const SurfaceDomain* scaled_domain(const std::string& mesh, double max_circumradius) {
  static SurfaceCache cache;
  std::string spec = mesh;
  if (mesh.rfind("shape:", 0) != 0) {
    const std::filesystem::path path = std::filesystem::path(PHYSARUM_SHARED_MESHES) / mesh;
    if (!std::filesystem::exists(path)) return nullptr;
    spec = path.string();
  }
  return &cache.get(bench_surface(spec, max_circumradius)).domain;
}

}  // namespace physarum::bench
