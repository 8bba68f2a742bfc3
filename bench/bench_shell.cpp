// The growth model's shell solve against the sheet's vertex count (10^3 to 10^5): one growth step of
// a disk (a tenth of the way to a spherical cap's metric, from flat with the seeded nudge: the
// hardest step, the buckling) solved to equilibrium by Newton's method, and a whole shape (30 steps
// to the cap). Counters: Newton iterations, and seconds per iteration (the Hessian's assembly and
// projection, CHOLMOD's factorization, the solve and the line search).
#include "api/session.hpp"
#include "common/mesh/shapes.hpp"
#include "common/scene/scene.hpp"
#include "common/shell/rest_metric.hpp"
#include "common/shell/sheet_perturbation.hpp"
#include "common/numerics/shared_cholesky.hpp"
#include "common/shell/shell_equilibrium.hpp"

#include <Eigen/OrderingMethods>
#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace physarum {
namespace {

struct Sheet {
  PolygonSoup soup;
  ShellTopology topology;
  ShellRestState flat;
};

Sheet disk_sheet(int rings) {
  Sheet sheet{disk_soup(rings), {}, {}};
  std::vector<std::array<int, 3>> faces;
  for (std::size_t p = 0; p + 1 < sheet.soup.polygon_start.size(); ++p) {
    const int* c = sheet.soup.corner_vertex.data() + sheet.soup.polygon_start[p];
    faces.push_back({c[0], c[1], c[2]});
  }
  sheet.topology = build_shell_topology(static_cast<int>(sheet.soup.positions.size()), faces);
  sheet.flat = rest_state_of(sheet.topology, sheet.soup.positions);
  return sheet;
}

// The rest state `fraction` of the way to a spherical cap's metric (centre stretched by 1.25).
ShellRestState toward_cap(const Sheet& sheet, double fraction) {
  ShellRestState grown = sheet.flat;
  for (std::size_t f = 0; f < grown.face_metric.size(); ++f) {
    const auto& t = sheet.topology.faces[f];
    const auto& p = sheet.soup.positions;
    const double rho = ((p[t[0]] + p[t[1]] + p[t[2]]) / 3).norm();
    const double s = 1.0 + fraction * (1.25 / (1 + rho * rho / 4) - 1.0);
    grown.face_metric[f] *= s * s;
  }
  return grown;
}

const ShellMaterial kSheetMaterial{0.002, 1e7, 0.3};

void BM_ShellGrowthStep(benchmark::State& state) {
  const Sheet sheet = disk_sheet(static_cast<int>(state.range(0)));
  const ShellRestState grown = toward_cap(sheet, 0.1);
  const ShellEquilibrium solver(sheet.topology, kSheetMaterial, central_face(sheet.topology, sheet.soup.positions));
  int iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::vector<Eigen::Vector3d> positions = sheet.soup.positions;
    perturb_out_of_plane(sheet.topology, positions, 1e-4, 1, 1);
    state.ResumeTiming();
    const NewtonReport report = solver.solve(positions, grown, NewtonSettings{});
    if (!report.converged) state.SkipWithError("Newton did not converge");
    iterations = report.iterations;
  }
  state.counters["vertices"] = static_cast<double>(sheet.soup.positions.size());
  state.counters["newton_iterations"] = iterations;
  state.counters["s_per_iteration"] = benchmark::Counter(
      static_cast<double>(std::max(iterations, 1)) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The whole shape: 30 growth steps to the cap's metric, each from the last equilibrium.
void BM_ShellThirtyGrowthSteps(benchmark::State& state) {
  const Sheet sheet = disk_sheet(static_cast<int>(state.range(0)));
  const ShellEquilibrium solver(sheet.topology, kSheetMaterial, central_face(sheet.topology, sheet.soup.positions));
  int iterations = 0, factorizations = 0;
  for (auto _ : state) {
    std::vector<Eigen::Vector3d> positions = sheet.soup.positions;
    iterations = factorizations = 0;
    std::vector<Eigen::Vector3d> previous = positions;
    for (int step = 1; step <= 30; ++step) {
      if (state.range(1)) {
        // Predictor: the last step's displacement once more.
        const std::vector<Eigen::Vector3d> current = positions;
        for (std::size_t v = 0; v < positions.size(); ++v) positions[v] += current[v] - previous[v];
        previous = current;
      }
      perturb_out_of_plane(sheet.topology, positions, 1e-4, 1, static_cast<std::uint32_t>(step));
      const NewtonReport report = solver.solve(positions, toward_cap(sheet, step / 30.0), NewtonSettings{});
      if (!report.converged) state.SkipWithError("Newton did not converge");
      iterations += report.iterations;
      factorizations += report.factorizations;
    }
  }
  state.counters["vertices"] = static_cast<double>(sheet.soup.positions.size());
  state.counters["newton_iterations"] = iterations;
  state.counters["factorizations"] = factorizations;
}

// 18, 55, 182 rings: 1,027, 9,241 and 99,919 vertices.
BENCHMARK(BM_ShellGrowthStep)->Arg(18)->Arg(55)->Arg(182)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ShellThirtyGrowthSteps)->Args({18, 0})->Args({18, 1})->Args({55, 0})->Args({55, 1})->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace physarum
namespace physarum {
namespace {
// The parts of one Newton iteration at 9,241 vertices, on a buckled sheet.
void BM_ShellIterationParts(benchmark::State& state) {
  const Sheet sheet = disk_sheet(55);
  const ShellRestState grown = toward_cap(sheet, 0.1);
  const ShellEnergy energy(sheet.topology, kSheetMaterial);
  std::vector<Eigen::Vector3d> positions = sheet.soup.positions;
  perturb_out_of_plane(sheet.topology, positions, 1e-2, 1, 1);
  const Eigen::VectorXd x = to_coordinates(positions);
  Eigen::SparseMatrix<double> h;
  energy.hessian(x, grown, true, h);
  const double shift = 1e-3 * h.diagonal().maxCoeff();
  for (int i = 0; i < h.rows(); ++i) h.coeffRef(i, i) += shift;
  // Orderings: METIS on the 3n coordinates (SharedCholesky's default), or AMD on the n vertices with
  // each vertex's three coordinates kept together.
  std::vector<int> block_order;
  if (state.range(0) == 5) {
    Eigen::SparseMatrix<double> vertex_graph(sheet.topology.vertex_count, sheet.topology.vertex_count);
    std::vector<Eigen::Triplet<double>> entries;
    for (int k = 0; k < h.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(h, k); it; ++it) entries.emplace_back(it.row() / 3, it.col() / 3, 1.0);
    vertex_graph.setFromTriplets(entries.begin(), entries.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation;
    Eigen::AMDOrdering<int>()(vertex_graph, permutation);
    std::vector<int> vertex_order(static_cast<std::size_t>(sheet.topology.vertex_count));
    for (int v = 0; v < sheet.topology.vertex_count; ++v) vertex_order[static_cast<std::size_t>(v)] = permutation.indices()(v);
    for (int v : vertex_order)
      for (int c = 0; c < 3; ++c) block_order.push_back(3 * v + c);
  }
  SharedCholesky cholesky(h, block_order.empty() ? nullptr : &block_order);
  for (auto _ : state) {
    switch (state.range(0)) {
      case 0: benchmark::DoNotOptimize(energy.energy(x, grown)); break;
      case 1: benchmark::DoNotOptimize(energy.gradient(x, grown)); break;
      case 2: energy.hessian(x, grown, false, h); break;
      case 3: energy.hessian(x, grown, true, h); break;
      case 4:
      case 5: cholesky.release_factors(); benchmark::DoNotOptimize(cholesky.factor(h, "h")); break;
    }
  }
}
BENCHMARK(BM_ShellIterationParts)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->UseRealTime();
}  // namespace
}  // namespace physarum

// The whole growth model through the library, on each backend: a 9,241-vertex disk's 4,000
// reaction–diffusion steps (Fig. 9's rings) and its first growth steps (arg 1), reporting where the
// time goes: the reaction–diffusion steps against the shell's solves (counters, seconds).
namespace physarum {
namespace {
void BM_GrowthModelShares(benchmark::State& state) {
  nlohmann::json scene;
  std::ifstream(std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/growth_rings.json") >> scene;
  scene["schedule"]["growth_steps"] = state.range(1);
  SessionOptions options;
  options.backend = state.range(0) == 0 ? "reference" : "opencl";
  options.use_map_cache = false;
  for (auto _ : state) {
    Session session(scene_from_json(scene), options);
    const GrowthSimulation& growth = *session.growth();
    session.step(4000 + state.range(1));
    double shell = 0.0;
    for (const GrowthStepRecord& r : growth.records()) shell += r.seconds;
    state.counters["reaction_seconds"] = growth.reaction_seconds();
    state.counters["growth_seconds"] = shell;
    state.counters["newton_iterations"] = growth.records().empty() ? 0 : growth.records().front().newton_iterations;
  }
}
BENCHMARK(BM_GrowthModelShares)->Args({0, 3})->Args({1, 3})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
}  // namespace
}  // namespace physarum
