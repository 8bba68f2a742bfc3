#pragma once
// The per-seed metrics of the differential harness for a reaction-diffusion system: the counterpart
// of common/harness/comparison_metrics.hpp (which measures the agent model), judged by the same equivalence
// test. One seed = one system built with that seed (its noise and spots), run for the comparison's
// burn-in and then sampled over its duration; each metric is time-averaged, so a seed contributes
// ONE number per metric (the seed, not the vertex, is the unit of replication). All are dimensionless.
//
//   mean_<m>              area-weighted mean of morphogen m, every morphogen     relative margin
//   cv2_<m>               area-weighted variance / mean^2 of morphogen m         relative margin
//   coverage_<p>_<f>range area fraction where the preview morphogen p lies above  absolute margin
//                         min + f (max - min) of the snapshot, f = 0.25, 0.5, 0.75
//   harmonic_band_k       the preview morphogen's share of its variance in band   relative margin
//                         k of the manifold harmonics at the pattern's scale or
//                         finer (only where the computed eigenpairs reach it)
//   radial_band_k         the same share in radial bands of the FFT power        relative margin
//                         spectrum (flat domains only)
//   scale_band_{a}l_{b}l  between two triangulations, in place of the harmonic   relative margin
//                         bands: the share of the variance between a and b
//                         pattern scales l, measured on the arms' common sampling
//                         (common/harness/smoothing_spectrum.hpp)
//
// Why each is there:
//   * the means are mass balance: a wrong feed or decay moves them first (the fault rd-no-feed
//     starves u and with it v), and they are the quantity stats.csv reports;
//   * cv2 is the pattern's contrast: a uniform state has 0, and a fault that suppresses the
//     instability (rd-swap-diffusion: D_u < D_v leaves Turing's model stable) shows here even
//     where the means hardly move;
//   * the coverages describe the SHAPE of the value distribution (spots vs. stripes vs. labyrinth
//     cover different shares of the area) whatever the model's units: thresholds are fractions of
//     the snapshot's own range, so the same definition serves every model. Their margins are shares
//     of the area (absolute), as for the agent model: a relative margin would make the rare top
//     coverage the noisiest metric;
//   * the band shares say at which wavelengths the contrast sits: a wrong diffusion rate moves the
//     pattern's wavelength by sqrt of its error, which neither means nor coverages see. They are
//     shares of the variance (cv2 holds the amplitude), so seed-to-seed differences in contrast
//     do not add to their spread.
//
// Margins come from the scene's compare_margin_* keys (common/scene/scene.hpp ComparisonSettings), read
// as: compare_margin_mean relative on each mean, compare_margin_detail relative on each cv2 (the
// agent model's detail energies are the same kind of quantity: a variance over a mean squared),
// compare_margin_coverage absolute, compare_margin_spectrum relative on the band shares.
#include "common/harness/comparison_metrics.hpp"
#include "common/surface/eigenvalues.hpp"
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/simulation/simulation_backend.hpp"

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace physarum {

// The length scale of a reaction-diffusion system's patterns, estimated before any run: the
// distance the fastest-diffusing morphogen spreads in the kinetics' fastest time,
//   l = 2 pi sqrt(D_max / r),
// r the spectral radius of the kinetics' Jacobian at `state` (one value per morphogen; the
// coefficients at their area-weighted means; central differences), D_m = trace(K_m) / trace(L)
// (exactly the rate for a uniform isotropic one, its average otherwise). Where diffusion is faster
// than this, a pattern is smoothed away; Turing's fastest-growing wavelength is l / (D_u/D_v)^(1/4)
// for Turk's model, Gray-Scott's spots are about l across. +infinity when nothing diffuses or the
// kinetics have no rate there.
double reaction_diffusion_pattern_scale(const ReactionDiffusionSystem& system, const SurfaceDomain& domain,
                                        const std::vector<double>& state);

// Modes coarser than this many pattern scales are left out of the band shares (see
// common/harness/harmonic_bands.hpp: coarse modes see where the spots happen to lie, which differs from
// seed to seed more than any affordable number of seeds averages away).
inline constexpr double kCoarsestBandScale = 2.0;

// The scales, in pattern scales, between which the scale bands lie (up to kCoarsestBandScale).
inline constexpr double kScaleBandEdges[] = {0.25, 0.5, 1.0, 2.0};

// The fractions of the snapshot's range above which the preview morphogen's coverage is measured.
inline constexpr double kCoverageRangeFractions[] = {0.25, 0.5, 0.75};

class ReactionDiffusionMetrics {
 public:
  // `scene` must be a reaction-diffusion scene (InputError otherwise); it sets the metric set and
  // margins only. Computes the eigenpairs for the band shares (scene.comparison.eigenpairs) when
  // share.discretisation, and the plane coordinates for the radial spectrum when the surface is flat.
  ReactionDiffusionMetrics(const PreparedSurface& surface, const Scene& scene, double pattern_scale, ArmsShare share = {});

  const std::vector<MetricInfo>& metrics() const { return metrics_; }
  // Why metrics of the documented set were left out on this scene (one sentence each).
  const std::vector<std::string>& left_out() const { return left_out_; }
  double pattern_scale() const { return pattern_scale_; }

  // The metrics of one state: every morphogen's values per intrinsic vertex, in the system's order.
  std::vector<double> snapshot(const std::vector<IntrinsicVertexData<double>>& morphogens) const;

  // Runs `sim` (a fresh system of `scene`, the arm's own) for the scene's compare burn-in, then
  // samples every compare_sample_interval over compare_duration and returns the time averages.
  // InputError when a morphogen stops being finite (the run diverged: say which seed).
  // `final_field`, when given, receives the preview morphogen's field at the end.
  std::vector<double> measure_seed(SimulationBackend& sim, const Scene& scene,
                                   IntrinsicVertexData<double>* final_field = nullptr) const;

 private:
  const SurfaceDomain& domain_;
  int morphogens_ = 0;
  int preview_ = 0;
  double pattern_scale_ = 0.0;
  Eigenpairs eigenpairs_;
  std::vector<int> harmonic_band_of_mode_;
  int harmonic_bands_ = 0;
  std::vector<Eigen::Vector2d> plane_xy_;
  int grid_size_ = 64;
  int radial_first_ = 1;  // the coarsest radius used (wavelength side / r at most the coarsest scale)
  int radial_bands_ = 0;
  // Between two triangulations: the scale bands on the common sampling.
  void add_scale_bands(const PreparedSurface& surface, const ArmsShare& share, const ComparisonSettings& c);
  std::shared_ptr<const CommonSampling> sampling_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> to_samples_;
  std::unique_ptr<SmoothingSpectrum> spectrum_;
  std::vector<MetricInfo> metrics_;
  std::vector<std::string> left_out_;
};

}  // namespace physarum
