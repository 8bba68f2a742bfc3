#include "common/comparison_metrics.hpp"

#include "common/errors.hpp"
#include "common/field_statistics.hpp"
#include "common/spectral_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {

ComparisonMetrics::ComparisonMetrics(const SceneSurface& surface, const Scene& scene)
    : domain_(surface.domain), settings_(scene.comparison), time_step_(scene.time_step) {
  U_ = uniform_steady_state(scene, domain_.total_area);
  eigenpairs_ = smallest_eigenpairs(domain_, settings_.eigenpairs, true);
  try {
    plane_xy_ = planar_vertex_coordinates(domain_, surface.simulated);
    flat_ = true;
  } catch (const InputError&) {
    flat_ = false;  // curved: the manifold harmonics are the spectrum
  }

  const ComparisonSettings& c = settings_;
  metrics_.push_back({"mean_over_U", MarginKind::Absolute, c.margin_mean});
  for (const char* name : {"coverage_0.5U", "coverage_1U", "coverage_2U"})
    metrics_.push_back({name, MarginKind::Absolute, c.margin_coverage});
  // Bands equal in sqrt(lambda) from 0 may hold no eigenpair (the lowest, on a sphere, holds only
  // the constant mode); such a band has no power to compare and is not a metric.
  const ManifoldHarmonicBands layout = manifold_harmonic_band_powers(
      domain_, eigenpairs_, std::vector<double>(static_cast<size_t>(domain_.vertex_count), 1.0), c.spectrum_bands);
  for (int b = 0; b < c.spectrum_bands; ++b)
    if (layout.modes[static_cast<size_t>(b)] > 0) {
      harmonic_bands_.push_back(b);
      metrics_.push_back({"harmonic_band_" + std::to_string(b + 1), MarginKind::Relative, c.margin_spectrum});
    }
  if (flat_)
    for (int b = 1; b <= c.spectrum_bands; ++b)
      metrics_.push_back({"radial_band_" + std::to_string(b), MarginKind::Relative, c.margin_spectrum});
  metrics_.push_back({"agent_density", MarginKind::Relative, c.margin_density});
}

std::vector<double> ComparisonMetrics::snapshot(const SimulationBackend& sim) const {
  std::vector<double> m;
  m.reserve(metrics_.size());
  const FieldStatistics stats = sim.field_statistics(U_);
  m.push_back(stats.mean / U_);
  for (double coverage : stats.coverage) m.push_back(coverage);

  const std::vector<double> field = sim.concentration_values();
  const ManifoldHarmonicBands bands =
      manifold_harmonic_band_powers(domain_, eigenpairs_, field, settings_.spectrum_bands);
  for (int b : harmonic_bands_) m.push_back(bands.power[static_cast<size_t>(b)]);

  if (flat_) {
    // Radii 1 .. grid/2 (whole annuli) in equal bands; radius 0 is the mean, left out.
    const RadialSpectrum spectrum = radial_power_spectrum(plane_xy_, domain_.face_vertices, field, grid_size_);
    const int top = grid_size_ / 2;
    std::vector<double> band(static_cast<size_t>(settings_.spectrum_bands), 0.0);
    for (int r = 1; r <= top; ++r) {
      const int b = std::min(settings_.spectrum_bands - 1, (r - 1) * settings_.spectrum_bands / top);
      band[static_cast<size_t>(b)] += spectrum.power[static_cast<size_t>(r)] * spectrum.count[static_cast<size_t>(r)];
    }
    for (double p : band) m.push_back(p);
  }

  m.push_back(agent_density_dispersion(sim.agent_faces(), domain_.face_area).dispersion);
  return m;
}

std::vector<double> ComparisonMetrics::measure_seed(SimulationBackend& sim) const {
  const auto steps_for = [&](double seconds) { return std::max<long long>(0, std::llround(seconds / time_step_)); };
  const long long burn_in = steps_for(settings_.burn_in);
  const long long every = std::max<long long>(1, steps_for(settings_.sample_interval));
  const long long samples = std::max<long long>(1, steps_for(settings_.duration) / every);
  // The field starts at its analytic steady mean U, so the burn-in only has to let the pattern form.
  sim.fill_concentration(U_);
  sim.run(burn_in);
  std::vector<double> sum(metrics_.size(), 0.0);
  for (long long s = 0; s < samples; ++s) {
    sim.run(every);
    const std::vector<double> m = snapshot(sim);
    for (size_t i = 0; i < m.size(); ++i) sum[i] += m[i];
  }
  for (double& x : sum) x /= static_cast<double>(samples);
  return sum;
}

}  // namespace physarum
