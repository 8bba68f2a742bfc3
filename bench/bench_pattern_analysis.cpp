// Pattern analysis (`physarum analyze`, common/pattern/pattern_analysis.hpp) of a hexagonal lattice of
// Gaussian spots (spacing 0.1, so ~100 spots) on the unit square cut into N x N cells, N = 128 .. 512
// (17k .. 263k vertices). The spacing is the costly part: one fast-marching run for the Voronoi
// labels over the whole surface, then one per spot over its own and its neighbours' cells.
//   BM_SegmentPattern  the clipping and connected regions alone
//   BM_AnalyzePattern  everything analysis.json reports
#include "common/pattern/pattern_analysis.hpp"
#include "common/pattern/pattern_segmentation.hpp"

#include <benchmark/benchmark.h>

#include <cmath>

namespace physarum::bench {
namespace {

struct LatticeField {
  InputMesh mesh;
  InputVertexData<double> field;
  double threshold = 0.0;
};

LatticeField lattice(int n) {
  LatticeField l;
  l.mesh.source = "bench grid";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) l.mesh.positions.emplace_back(double(i) / n, double(j) / n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      l.mesh.triangles.push_back({a, b, c});
      l.mesh.triangles.push_back({a, c, d});
    }
  const double s = 0.1, row = s * std::sqrt(3.0) / 2.0, sigma = 0.015;
  l.field = InputVertexData<double>(l.mesh.positions.size(), 0.0);
  for (size_t v = 0; v < l.mesh.positions.size(); ++v) {
    const Eigen::Vector3d& p = l.mesh.positions[v];
    // The nearest lattice site's bump (sites further away add less than 1e-9).
    const int j = static_cast<int>(std::lround((p.y() - 0.05) / row));
    double f = 0.0;
    for (int jj = j - 1; jj <= j + 1; ++jj) {
      const double x0 = 0.05 + (jj % 2 != 0 ? 0.5 * s : 0.0), y = 0.05 + jj * row;
      const int k = static_cast<int>(std::lround((p.x() - x0) / s));
      for (int kk = k - 1; kk <= k + 1; ++kk) {
        const double dx = p.x() - (x0 + kk * s), dy = p.y() - y;
        f = std::max(f, std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma)));
      }
    }
    l.field[v] = f;
  }
  l.threshold = std::exp(-0.5);  // spots of radius sigma
  return l;
}

void BM_SegmentPattern(benchmark::State& state) {
  const LatticeField l = lattice(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(segment_pattern(l.mesh, l.field, l.threshold));
  state.counters["vertices"] = static_cast<double>(l.mesh.positions.size());
}
BENCHMARK(BM_SegmentPattern)->Arg(128)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond);

void BM_AnalyzePattern(benchmark::State& state) {
  const LatticeField l = lattice(static_cast<int>(state.range(0)));
  PatternAnalysisOptions options;
  options.threshold = l.threshold;
  size_t spots = 0;
  for (auto _ : state) spots = analyze_pattern(l.mesh, l.field, options).regions.size();
  state.counters["vertices"] = static_cast<double>(l.mesh.positions.size());
  state.counters["spots"] = static_cast<double>(spots);
}
BENCHMARK(BM_AnalyzePattern)->Arg(128)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace physarum::bench
