// Geodesic distance on unit icospheres (common/map_tools/heat_geodesic.hpp, common/map_tools/fast_marching.hpp), built
// in code (no scene), the sizes of the comparison with potpourri3d: level 6 (81,920 faces)
// and level 8 (1,310,720 faces). The targets at ~10^6 faces: heat factor <= 10 s once,
// heat solve <= 0.2 s per new source set, fast marching <= 2 s.
//   BM_HeatGeodesicFactor  building HeatGeodesicSolver: M + tL and the pinned L, factored (CHOLMOD)
//   BM_HeatGeodesicSolve   one distance() from a vertex, after the factorization
//   BM_FastMarching        one distance() from a vertex (the obtuse-corner splitting is built once
//                          per process and reported as build_s)
//   BM_CholeskySolve       one solve with the factor of M + tL (t = h^2), the heat method's step 1:
//                          /level/0 CHOLMOD's own cholmod_solve (serial), /level/1 ours
//                          (common/numerics/supernodal_solve.hpp: by subtrees on all cores above its size
//                          threshold), /level/2 ours forced serial, /level/3 ours forced parallel
//                          (where the threshold should sit); factor_entries is what each solve
//                          streams twice
// Each reports max_error_pct_pi: the largest |computed - arccos(p.q)| over all vertices, in % of pi.
#include "common/map_tools/fast_marching.hpp"
#include "common/map_tools/heat_geodesic.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/numerics/shared_cholesky.hpp"
#include "common/surface/surface_domain.hpp"
#include "tests/pheromone_test_meshes.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <utility>

namespace physarum::bench {
namespace {

struct Icosphere {
  InputMesh mesh;
  SurfaceDomain domain;
};

const Icosphere& icosphere(int level) {
  static std::map<int, std::unique_ptr<Icosphere>> cache;
  auto& entry = cache[level];
  if (!entry) {
    entry = std::make_unique<Icosphere>();
    entry->mesh = testing::make_icosphere(level);
    entry->domain = build_surface_domain(intrinsic_mesh_from_input(entry->mesh));
  }
  return *entry;
}

double max_error_pct_pi(const Icosphere& sphere, const IntrinsicVertexData<double>& distance, int source) {
  double worst = 0.0;
  const Eigen::Vector3d& p = sphere.mesh.positions[static_cast<size_t>(source)];
  for (size_t v = 0; v < distance.size(); ++v) {
    const double exact = std::acos(std::clamp(p.dot(sphere.mesh.positions[v]), -1.0, 1.0));
    worst = std::max(worst, std::abs(distance[v] - exact));
  }
  return 100.0 * worst / std::numbers::pi;
}

void faces_counter(benchmark::State& state, const Icosphere& sphere) {
  state.counters["intrinsic_faces"] = sphere.domain.face_count;
}

void BM_HeatGeodesicFactor(benchmark::State& state) {
  const Icosphere& sphere = icosphere(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    HeatGeodesicSolver solver(sphere.domain);
    benchmark::DoNotOptimize(solver.time());
  }
  faces_counter(state, sphere);
}

void BM_HeatGeodesicSolve(benchmark::State& state) {
  const Icosphere& sphere = icosphere(static_cast<int>(state.range(0)));
  const HeatGeodesicSolver solver(sphere.domain);
  IntrinsicVertexData<double> distance;
  int source = 0;
  for (auto _ : state) {
    distance = solver.distance({source});
    benchmark::DoNotOptimize(distance.data());
  }
  faces_counter(state, sphere);
  state.counters["max_error_pct_pi"] = max_error_pct_pi(sphere, distance, source);
}

void BM_FastMarching(benchmark::State& state) {
  const Icosphere& sphere = icosphere(static_cast<int>(state.range(0)));
  const auto start = std::chrono::steady_clock::now();
  const FastMarchingGeodesics marching(sphere.domain);
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  IntrinsicVertexData<double> distance;
  for (auto _ : state) {
    distance = marching.distance({0});
    benchmark::DoNotOptimize(distance.data());
  }
  faces_counter(state, sphere);
  state.counters["build_s"] = build_s;
  state.counters["max_error_pct_pi"] = max_error_pct_pi(sphere, distance, 0);
}

struct HeatSystem {
  std::unique_ptr<SharedCholesky> cholesky;
  int index = -1;
  Eigen::VectorXd rhs;
};

// The factor of M + tL on an icosphere, solved in parallel from `min_parallel_entries` on.
const HeatSystem& heat_system(int level, std::size_t min_parallel_entries) {
  static std::map<std::pair<int, std::size_t>, std::unique_ptr<HeatSystem>> cache;
  auto& entry = cache[{level, min_parallel_entries}];
  if (!entry) {
    const SurfaceDomain& domain = icosphere(level).domain;
    const double h = mean_intrinsic_edge_length(domain);
    Eigen::SparseMatrix<double> a = h * h * Eigen::SparseMatrix<double>(domain.laplacian.to_eigen());
    for (int v = 0; v < domain.vertex_count; ++v) a.coeffRef(v, v) += domain.vertex_mass[static_cast<size_t>(v)];
    a.makeCompressed();
    entry = std::make_unique<HeatSystem>();
    entry->cholesky = std::make_unique<SharedCholesky>(a, nullptr, min_parallel_entries);
    entry->index = entry->cholesky->factor(a, "M + tL");
    entry->rhs = Eigen::VectorXd::Zero(a.rows());
    entry->rhs[0] = 1.0;
  }
  return *entry;
}

void BM_CholeskySolve(benchmark::State& state) {
  const int variant = static_cast<int>(state.range(1));
  const std::size_t threshold = variant == 2 ? std::numeric_limits<std::size_t>::max() : variant == 3 ? 0 : kMinParallelSolveEntries;
  const HeatSystem& system = heat_system(static_cast<int>(state.range(0)), threshold);
  const bool ours = variant != 0;
  Eigen::VectorXd x;
  for (auto _ : state) {
    x = ours ? system.cholesky->solve(system.index, system.rhs) : system.cholesky->cholmod_reference_solve(system.index, system.rhs);
    benchmark::DoNotOptimize(x.data());
  }
  faces_counter(state, icosphere(static_cast<int>(state.range(0))));
  const SupernodalSolve& plan = system.cholesky->supernodal_solve(system.index);
  state.counters["factor_entries"] = static_cast<double>(plan.entries());
  state.counters["top_entries"] = static_cast<double>(plan.top_entries());
}

BENCHMARK(BM_HeatGeodesicFactor)->Arg(6)->Arg(8)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_HeatGeodesicSolve)->Arg(6)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FastMarching)->Arg(6)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CholeskySolve)->ArgsProduct({{4, 5, 6, 8}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CholeskySolve)->ArgsProduct({{4, 5, 6}, {2, 3}})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace physarum::bench
