// The growth model's shell solve: one growth step of a disk (a tenth of the way to a spherical
// cap's metric, from flat with the seeded nudge) solved to equilibrium by Newton's method, against the
// sheet's vertex count (10^3 to 10^5). Counters: Newton iterations, and seconds per iteration (the
// Hessian's assembly and projection, CHOLMOD's factorization, the solve and the line search).
#include "common/mesh/shapes.hpp"
#include "common/shell/rest_metric.hpp"
#include "common/shell/sheet_perturbation.hpp"
#include "common/shell/shell_equilibrium.hpp"

#include <benchmark/benchmark.h>

namespace physarum {
namespace {

void BM_ShellGrowthStep(benchmark::State& state) {
  const PolygonSoup soup = disk_soup(static_cast<int>(state.range(0)));
  std::vector<std::array<int, 3>> faces;
  for (std::size_t p = 0; p + 1 < soup.polygon_start.size(); ++p) {
    const int* c = soup.corner_vertex.data() + soup.polygon_start[p];
    faces.push_back({c[0], c[1], c[2]});
  }
  const ShellTopology topology = build_shell_topology(static_cast<int>(soup.positions.size()), faces);
  const ShellRestState flat = rest_state_of(topology, soup.positions);
  ShellRestState grown = flat;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const double rho = ((soup.positions[faces[f][0]] + soup.positions[faces[f][1]] + soup.positions[faces[f][2]]) / 3).norm();
    const double s = 1.0 + 0.1 * (1.25 / (1 + rho * rho / 4) - 1.0);
    grown.face_metric[f] *= s * s;
  }
  const ShellMaterial material{0.002, 1e7, 0.3};
  const ShellEquilibrium solver(topology, material, central_face(topology, soup.positions));
  int iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::vector<Eigen::Vector3d> positions = soup.positions;
    perturb_out_of_plane(topology, positions, 1e-4, 1, 1);
    state.ResumeTiming();
    const NewtonReport report = solver.solve(positions, grown, NewtonSettings{});
    if (!report.converged) state.SkipWithError("Newton did not converge");
    iterations = report.iterations;
  }
  state.counters["vertices"] = static_cast<double>(soup.positions.size());
  state.counters["newton_iterations"] = iterations;
  state.counters["s_per_iteration"] = benchmark::Counter(
      static_cast<double>(std::max(iterations, 1)) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
// 18, 55, 182 rings: 1,027, 9,241 and 99,919 vertices.
BENCHMARK(BM_ShellGrowthStep)->Arg(18)->Arg(55)->Arg(182)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace physarum
