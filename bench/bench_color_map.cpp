// Image-assisted colour maps (common/color/isomap_color_map.hpp) against the size of their graph: the
// all-pairs Dijkstra and the dense MDS matrix grow with the square of the distinct colours, which
// `IsomapOptions::max_colors` bounds (default 1500). The exemplar is a thick tube of random colours
// around a ramp (as a noisy photograph gives), so every run fills the node budget it is given.
#include "common/color/isomap_color_map.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>

namespace physarum::bench {
namespace {

ExemplarPixels noisy_ramp(int pixels) {
  std::mt19937 random(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ExemplarPixels p;
  for (int i = 0; i < pixels; ++i) {
    const double t = unit(random);
    SrgbColor c = {0.1 + 0.8 * t, 0.2 + 0.5 * t * t, 0.6 - 0.4 * t};
    for (double& v : c) v = std::clamp(v + 0.12 * (unit(random) - 0.5), 0.0, 1.0);
    p.colors.push_back(c);
    p.on_border.push_back(i < pixels / 50);
  }
  return p;
}

void BM_IsomapColorMap(benchmark::State& state) {
  static const ExemplarPixels pixels = noisy_ramp(40000);
  IsomapOptions options;
  options.max_colors = static_cast<int>(state.range(0));
  int nodes = 0;
  for (auto _ : state) nodes = isomap_color_map(pixels, "bench", "bench", options).graph_nodes;
  state.counters["graph_nodes"] = nodes;
}
BENCHMARK(BM_IsomapColorMap)->Arg(250)->Arg(500)->Arg(1000)->Arg(1500)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace physarum::bench
