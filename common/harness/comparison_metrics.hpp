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
//                        over area * mean^2
//   harmonic_band_k      manifold-harmonic band powers, k = 1..bands (bands of equal mode count), only
//                        where the computed eigenpairs reach the pattern's scale
//   radial_band_k        radially averaged FFT power in bands of radius (flat domains, likewise)
//   agent_density        dispersion of the agent density over faces (both arms on one discretisation)
//
// Each metric has a margin kind: absolute (mean / U, whose value is 1 whatever the scene, and the
// coverage fractions, whose margin is a share of the surface's area: a relative margin would make
// the rare coverage above 2 U, a few percent of the area, the noisiest metric of all) or relative to
// the reference arm's mean (spectral powers and the dispersion, whose scale depends on the scene).
#include "common/surface/eigenvalues.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/simulation/simulation_backend.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <memory>
#include <string>
#include <vector>

namespace physarum {

enum class MarginKind { Absolute, Relative };

struct MetricInfo {
  std::string name;
  MarginKind kind = MarginKind::Absolute;
  double margin = 0.0;  // absolute, or the fraction of the reference mean
};

// Which arms the metrics will compare. Metrics tied to one discretisation (the manifold-harmonic
// basis of one triangulation, the agent density per face with its shot-noise floor (F - 1) / N) mean
// the same thing in both arms only when both run on the same surface with the same agent count.
// Between two triangulations only continuum quantities compare, and a detail energy only at scales
// both resolve: at least kResolvedScaleInEdges mean edge lengths of the coarser one. Why 10: the
// piecewise-linear interpolant of a wave with n edges per wavelength misses 50 % of its energy at
// n = 3, 17 % at 6 and 6 % at 10 (computed by quadrature), so two triangulations whose edges
// differ by 1.5x disagree by about 9 % at 6 edges, as much as the detail margin, and by 3.5 % at 10.
struct ArmsShare {
  bool discretisation = true;
  double coarsest_edge_length = 0.0;  // m, when !discretisation: the coarser arm's mean edge length
};
constexpr double kResolvedScaleInEdges = 10.0;

// The edge length of an equilateral triangle of the domain's mean face area.
double mean_edge_length(const SurfaceDomain& domain);

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
  std::vector<double> measure_seed(SimulationBackend& sim, const Scene& scene, double steady_mean_over_U = 1.0) const;

  // The metrics of one snapshot of the simulation's current state; U is its scene's Eq. 5 value.
  std::vector<double> snapshot(const SimulationBackend& sim, double U) const;

 private:
  const SurfaceDomain& domain_;
  ComparisonSettings settings_;
  Eigenpairs eigenpairs_;
  int harmonic_bands_ = 0;
  int radial_bands_ = 0;
  bool agent_density_ = true;
  // The diffusion smoothers of the detail metrics: (M + t L) factorised once per scale.
  std::vector<std::shared_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>> smoothers_;
  std::vector<int> harmonic_band_of_mode_;  // band of each eigenpair, -1 for the constant modes
  bool flat_ = false;
  std::vector<Eigen::Vector2d> plane_xy_;
  int grid_size_ = 64;
  std::vector<MetricInfo> metrics_;
  std::vector<std::string> left_out_;
};

}  // namespace physarum
