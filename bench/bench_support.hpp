#pragma once
// What the benchmark suites share: the surfaces they run on (built once per process, skipped with a
// message when the shared meshes are absent) and the model parameters of the agent benchmarks.
#include "common/default_scene.hpp"
#include "common/input_mesh.hpp"
#include "common/intrinsic_triangulation.hpp"
#include "common/mesh_loading.hpp"
#include "common/scene.hpp"
#include "common/surface_domain.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace physarum::bench {

// The intrinsic domain of `mesh` (a shared mesh file name, or shape:NAME) scaled to 4 m^2 and
// refined to `max_circumradius` metres; nullptr when a shared mesh is absent.
inline const SurfaceDomain* scaled_domain(const std::string& mesh, double max_circumradius) {
  static std::map<std::pair<std::string, double>, std::unique_ptr<SurfaceDomain>> cache;
  const auto key = std::make_pair(mesh, max_circumradius);
  if (auto it = cache.find(key); it != cache.end()) return it->second.get();
  std::string spec = mesh;
  if (mesh.rfind("shape:", 0) != 0) {
    const std::filesystem::path path = std::filesystem::path(PHYSARUM_SHARED_MESHES) / mesh;
    if (!std::filesystem::exists(path)) return nullptr;
    spec = path.string();
  }
  InputMesh input = load_mesh(spec);
  const double area = compute_statistics(input).area;
  for (Eigen::Vector3d& p : input.positions) p *= std::sqrt(4.0 / area);
  IntrinsicTriangulation triangulation(input);
  triangulation.flip_to_delaunay();
  RefinementOptions refinement;
  refinement.max_circumradius = max_circumradius;
  triangulation.refine(refinement);
  auto domain = std::make_unique<SurfaceDomain>(build_surface_domain(triangulation.snapshot()));
  return cache.emplace(key, std::move(domain)).first->second.get();
}

// The default scene's parameters (tools/scenes/default.json) with `agents` agents.
inline Scene bench_scene(int agents) { return default_scene_parameters(agents); }

}  // namespace physarum::bench
