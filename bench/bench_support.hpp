#pragma once
// What the benchmark suites share: the surfaces they run on (built once per process through the
// shared surface loader, common/setup/scene_surface.hpp, skipped with a message when the shared meshes
// are absent) and the model parameters of the agent benchmarks (common/setup/workload.hpp).
#include "common/surface/surface_domain.hpp"
#include "common/setup/workload.hpp"

#include <filesystem>
#include <string>

namespace physarum::bench {

using physarum::bench_scene;

// The surfaces of this process, each built once.
inline SurfaceCache& surfaces() {
  static SurfaceCache cache;
  return cache;
}

// The mesh spec of `mesh` (a shared mesh file name, or shape:NAME); "" when a shared mesh is absent.
inline std::string mesh_spec(const std::string& mesh) {
  if (mesh.rfind("shape:", 0) == 0) return mesh;
  const std::filesystem::path path = std::filesystem::path(PHYSARUM_SHARED_MESHES) / mesh;
  return std::filesystem::exists(path) ? path.string() : "";
}

// The intrinsic domain of `mesh` scaled to 4 m^2 and refined to `max_circumradius` metres; nullptr
// when a shared mesh is absent.
inline const SurfaceDomain* scaled_domain(const std::string& mesh, double max_circumradius) {
  const std::string spec = mesh_spec(mesh);
  return spec.empty() ? nullptr : &surfaces().get(bench_surface(spec, max_circumradius)).domain;
}

}  // namespace physarum::bench
