// What the harness's common sampling costs (common/harness/common_sampling.hpp): arms on two
// triangulations of one input are measured at the finer arm's vertices. The held-out case of the
// resolution study: an 800-face decimated surface (tests/decimated_blob.hpp) at 4 m^2, its own
// triangulation against a refinement to max_circumradius 0.02 (~13,000 faces).
//   BM_CommonSamplingBuild       once per comparison: locating every sample in the coarse arm's
//                                triangles (point location through chord triangles)
//   BM_SampledPatternMetrics     once per snapshot of a coarse-arm seed (30 per seed at the default
//                                compare_duration / compare_sample_interval): reading its field at the
//                                samples and the smoothers of the kept detail scales there
#include "common/harness/common_sampling.hpp"
#include "common/harness/smoothing_spectrum.hpp"
#include "decimated_blob.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

namespace physarum {
namespace {

struct Arms {
  std::shared_ptr<const PreparedSurface> coarse, fine;
};

const Arms& blob_arms() {
  static const Arms arms = [] {
    const std::string path = (std::filesystem::temp_directory_path() / "physarum_bench_blob.obj").string();
    testing::write_decimated_blob(path, 800);
    SurfaceSpec spec;
    spec.mesh = path;
    spec.scale_to_area = 4.0;
    Arms a;
    a.coarse = std::make_shared<const PreparedSurface>(prepare_surface(spec));
    spec.max_circumradius = 0.02;
    a.fine = std::make_shared<const PreparedSurface>(prepare_surface(spec));
    return a;
  }();
  return arms;
}

void BM_CommonSamplingBuild(benchmark::State& state) {
  const Arms& arms = blob_arms();
  for (auto _ : state) {
    const CommonSampling sampling(arms.coarse, arms.fine);
    benchmark::DoNotOptimize(sampling.from(*arms.coarse).nonZeros());
  }
  state.counters["samples"] = arms.fine->domain.vertex_count;
  state.counters["coarse_vertices"] = arms.coarse->domain.vertex_count;
}

// `scales` detail scales of the held-out case (sensor distance 0.06 m: 4 d = 0.24 m is the one the
// sampling resolves; 2 for the resolved case's 2 d and 4 d).
void BM_SampledPatternMetrics(benchmark::State& state) {
  const Arms& arms = blob_arms();
  const CommonSampling sampling(arms.coarse, arms.fine);
  const auto to_samples = sampling.from(*arms.coarse);
  std::vector<double> scales;
  for (int k = 0; k < state.range(0); ++k) scales.push_back(0.24 * (1 << k));
  const SmoothingSpectrum spectrum(sampling.domain(), scales);
  Eigen::VectorXd field = Eigen::VectorXd::Random(arms.coarse->domain.vertex_count).array() + 2.0;
  for (auto _ : state) {
    const Eigen::VectorXd read = CommonSampling::read(to_samples, field);
    benchmark::DoNotOptimize(spectrum.of(read, 1.0).detail.front());
  }
  state.counters["samples"] = arms.fine->domain.vertex_count;
}

BENCHMARK(BM_CommonSamplingBuild)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SampledPatternMetrics)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace physarum
