#pragma once
// The per-seed metrics of the differential harness (its long horizon: independent seeds,
// time-averaged metrics): for one run of one backend, every metric sampled at a fixed interval after
// the burn-in and time-averaged, so a seed contributes ONE number per metric (the seed, not the
// vertex, is the unit of replication). All metrics are dimensionless.
//
// The default set is chosen from the scene's own scales, so that a scene nobody tuned can be decided
// (why each metric is in it is said where it is added, comparison_metrics.cpp):
//
//   mean_over_U          area-weighted mean concentration / U of Eq. 5
//   coverage_{0.5,1,2}U  area fraction above 0.5 U, U, 2 U
//   detail_{m}d          high-pass energy at m = 1/4, 1/2, 1, 2, 4 sensor distances d: the energy of
//                        u - G u, G the diffusion smoother (M + t L)^-1 M with t = (m d / 2 pi)^2,
//                        over area * mean^2 (common/harness/smoothing_spectrum.hpp)
//   scale_band_{a}d_{b}d between two triangulations: the energy of G_a u - G_b u between consecutive
//                        detail scales, a spectrum that needs no shared eigenbasis
//   harmonic_band_k      manifold-harmonic band powers, k = 1..bands (bands of equal mode count), only
//                        where the computed eigenpairs reach the pattern's scale
//   radial_band_k        radially averaged FFT power in bands of radius (flat domains, likewise)
//   agent_density        dispersion of the agent density over faces (both arms on one discretisation)
//
// Each metric has a margin kind: absolute (mean / U, whose value is 1 whatever the scene, and the
// coverage fractions, whose margin is a share of the surface's area: a relative margin would make
// the rare coverage above 2 U, a few percent of the area, the noisiest metric of all) or relative to
// the reference arm's mean (spectral powers and the dispersion, whose scale depends on the scene).
#include "common/harness/common_sampling.hpp"
#include "common/harness/smoothing_spectrum.hpp"
#include "common/surface/eigenvalues.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/simulation/simulation_backend.hpp"

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace physarum {

enum class MarginKind { Absolute, Relative };

struct MetricInfo {
  std::string name;
  MarginKind kind = MarginKind::Absolute;
  double margin = 0.0;  // absolute, or the fraction of the reference mean
  // A pattern-scale metric (detail energies, spectral bands): the longest wavelength it measures, in
  // metres. 0 for the others (means, coverages, dispersion), which a blurred pattern can keep.
  double scale = 0.0;
  // Measured on the common sampling of two triangulations (normalised by area x mean^2 there).
  bool on_common_sampling = false;
  // At a scale only the finer of two triangulations resolves (kResolvedScaleInEdges of the coarser's
  // edges): it can show that the arms differ, but an Equivalent verdict rests on the other metrics.
  bool difference_only = false;
  bool pattern_scale() const { return scale > 0.0; }
};

// Which arms the metrics will compare. Metrics tied to one discretisation (the manifold-harmonic
// basis of one triangulation, the agent density per face with its shot-noise floor (F - 1) / N) mean
// the same thing in both arms only when both run on the same surface with the same agent count.
// Between two triangulations of one input surface the pattern-scale metrics are measured on a common
// sampling (common/harness/common_sampling.hpp: the finer arm's vertices, both fields read there as
// their discretisations define them): the detail energies, and band powers between their scales in
// place of the harmonic bands. A scale is left out only when neither arm resolves it: when it spans
// fewer than kSampledScaleInEdges mean edges of the sampling. Why 6: the piecewise-linear interpolant
// of a wave with n edges per wavelength keeps (2 + cos(2 pi / n)) / 3 of its energy, 83 % at n = 6,
// 67 % at 4 and 50 % at 3; below 6 the sampling itself no longer carries the scale well enough to say
// how much of it an arm has.
struct ArmsShare {
  bool discretisation = true;
  // When !discretisation: the points both arms are measured at, or null when the arms do not
  // triangulate one input surface (then `no_sampling` says why, and the pattern-scale metrics are
  // left out).
  std::shared_ptr<const CommonSampling> sampling;
  std::string no_sampling;
};
constexpr double kSampledScaleInEdges = 6.0;

// A triangulation resolves a scale spanning kResolvedScaleInEdges of its mean edges: its
// piecewise-linear fields keep 94 % of a wave's energy at 10 edges (83 % at 6), so two triangulations
// that both resolve a scale measure it within ~3.5 % of each other, a third of the detail margin. A
// scale the finer arm resolves and the coarser does not is measured (difference_only): the coarser
// arm's representation alone loses up to 17 % of it (6 edges), so its equivalence would be decided
// by the discretisation, not the pattern; a difference larger than the margin is still a difference.
constexpr double kResolvedScaleInEdges = 10.0;

// A triangulation cannot represent a wavelength of fewer than kRepresentableScaleInEdges of its mean
// edges: its piecewise-linear fields keep at most half of such a wave's energy (at 3 edges), nothing
// of it below 2 (Nyquist), and put triangle-sized facets in its place. When the finer arm has power at
// such a scale (a sampled metric's mean at least kPatternPowerFloor, i.e. an rms of 10 % of the mean
// field at that scale), the coarser arm cannot have that pattern, and the metric is Different for
// that reason, whatever the coarser arm's facets happen to add up to there.
constexpr double kRepresentableScaleInEdges = 3.0;
constexpr double kPatternPowerFloor = 0.01;

// The scales two triangulations are measured at on their common sampling: the multiples of `unit`
// (increasing) whose scale the sampling resolves (kSampledScaleInEdges). Each other one is reported
// in `left_out` as "<label(multiple)>: its scale ... neither arm resolves it".
struct SampledScales {
  std::vector<double> multiples, scales;  // scales = multiples x unit, metres
};
SampledScales sampled_scales(const CommonSampling& sampling, const std::vector<double>& multiples, double unit,
                             const std::function<std::string(double multiple)>& label, std::vector<std::string>& left_out);
// The scale bands between consecutive sampled scales, named scale_band_{a}<unit>_{b}<unit>; a band is
// difference-only where the coarser arm does not resolve its finer end (kResolvedScaleInEdges).
std::vector<MetricInfo> scale_band_metrics(const SampledScales& sampled, const CommonSampling& sampling,
                                           const std::string& unit, double margin);
// Whether the coarser arm of `sampling` resolves `scale` (kResolvedScaleInEdges of its edges).
bool coarser_arm_resolves(const CommonSampling& sampling, double scale);

class ComparisonMetrics {
 public:
  // Computes the eigenpairs for the band powers (scene.comparison.eigenpairs) and, when the surface
  // is flat, the vertices' plane coordinates for the radial spectrum. `scene` sets the metric set
  // and margins only: how long a seed runs, at what time step, and the U it is measured against
  // belong to the scene of the arm being measured (measure_seed), so that two arms on one surface
  // can share these (costly) metrics whatever else they differ in.
  ComparisonMetrics(const PreparedSurface& surface, const Scene& scene, ArmsShare share = {});

  const std::vector<MetricInfo>& metrics() const { return metrics_; }
  // Why metrics of the documented set were left out on this scene (one sentence each).
  const std::vector<std::string>& left_out() const { return left_out_; }
  bool flat() const { return flat_; }

  // Runs one seed of `sim` (a fresh simulation of `scene`: the field is first set to its steady mean,
  // `steady_mean_over_U` times the scene's U of Eq. 5) for the scene's burn_in + duration, in steps of
  // the scene's time_step, and returns its time-averaged metrics, in the order of metrics() (mean and
  // coverage relative to U). `scene` must be the one `sim` simulates (the arm's own, not necessarily
  // the one these metrics were built from).
  // `final_field`, when given, receives the field the seed ends with.
  std::vector<double> measure_seed(SimulationBackend& sim, const Scene& scene, double steady_mean_over_U = 1.0,
                                   IntrinsicVertexData<double>* final_field = nullptr) const;

  // The metrics of one snapshot of the simulation's current state; U is its scene's Eq. 5 value.
  std::vector<double> snapshot(const SimulationBackend& sim, double U) const;

 private:
  // Between two triangulations: the detail energies and scale bands on the common sampling.
  void add_sampled_metrics(const PreparedSurface& surface, double sensor_distance, const ArmsShare& share);

  const SurfaceDomain& domain_;
  ComparisonSettings settings_;
  Eigenpairs eigenpairs_;
  int harmonic_bands_ = 0;
  int radial_bands_ = 0;
  bool agent_density_ = true;
  // The detail energies (and, between two triangulations, the band powers) and where they are
  // measured: this arm's own vertices, or the common sampling (to_samples_: empty when this arm's
  // vertices are the samples).
  std::unique_ptr<SmoothingSpectrum> spectrum_;
  bool scale_bands_ = false;
  std::shared_ptr<const CommonSampling> sampling_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> to_samples_;
  std::vector<int> harmonic_band_of_mode_;  // band of each eigenpair, -1 for the constant modes
  bool flat_ = false;
  std::vector<Eigen::Vector2d> plane_xy_;
  int grid_size_ = 64;
  std::vector<MetricInfo> metrics_;
  std::vector<std::string> left_out_;
};

}  // namespace physarum
