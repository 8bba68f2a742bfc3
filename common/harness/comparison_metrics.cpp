#include "common/setup/agent_inputs.hpp"
#include "common/harness/comparison_metrics.hpp"

#include "common/base/errors.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/harness/harmonic_bands.hpp"
#include "common/harness/spectral_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

namespace physarum {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Scales of the detail metrics, in sensor distances: the pattern's own scale is set by the sensor
// distance d (an agent steers towards pheromone d ahead of it, so strands and the gaps between them
// are a few d apart), and 1/4 .. 4 d brackets it from the strands' width to the network's cells.
constexpr double kDetailScales[] = {0.25, 0.5, 1.0, 2.0, 4.0};
constexpr double kCoarsestDetailScale = 4.0;

std::string metres(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g m", v);
  return text;
}

std::string detail_name(double multiple) {
  char name[32];
  std::snprintf(name, sizeof name, "detail_%gd", multiple);
  return name;
}

}  // namespace

SampledScales sampled_scales(const CommonSampling& sampling, const std::vector<double>& multiples, double unit,
                             const std::function<std::string(double multiple)>& label, std::vector<std::string>& left_out) {
  SampledScales out;
  const double h = sampling.edge_length();
  for (double multiple : multiples) {
    const double scale = multiple * unit;
    if (scale < kSampledScaleInEdges * h) {
      left_out.push_back(label(multiple) + ": its scale " + metres(scale) + " spans fewer than " +
                         std::to_string(static_cast<int>(kSampledScaleInEdges)) + " edges of the finer arm's triangulation (" +
                         metres(h) + " each, the common sampling): neither arm resolves it");
      continue;
    }
    out.multiples.push_back(multiple);
    out.scales.push_back(scale);
  }
  return out;
}

bool coarser_arm_resolves(const CommonSampling& sampling, double scale) {
  return scale >= kResolvedScaleInEdges * sampling.coarser_edge_length();
}

std::vector<MetricInfo> scale_band_metrics(const SampledScales& sampled, const CommonSampling& sampling,
                                           const std::string& unit, double margin) {
  std::vector<MetricInfo> bands;
  for (size_t k = 1; k < sampled.scales.size(); ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "scale_band_%g%s_%g%s", sampled.multiples[k - 1], unit.c_str(), sampled.multiples[k],
                  unit.c_str());
    bands.push_back({name, MarginKind::Relative, margin, sampled.scales[k], true,
                     !coarser_arm_resolves(sampling, sampled.scales[k - 1])});
  }
  return bands;
}

void ComparisonMetrics::add_sampled_metrics(const PreparedSurface& surface, double d, const ArmsShare& share) {
  const ComparisonSettings& c = settings_;
  if (!share.sampling) {
    left_out_.push_back("detail energies and scale bands: " + share.no_sampling + ", so there is no common sampling to measure them on");
    return;
  }
  sampling_ = share.sampling;
  to_samples_ = sampling_->from(surface);
  const SampledScales sampled = sampled_scales(*sampling_, std::vector<double>(std::begin(kDetailScales), std::end(kDetailScales)),
                                               d, detail_name, left_out_);
  for (size_t k = 0; k < sampled.scales.size(); ++k)
    metrics_.push_back({detail_name(sampled.multiples[k]), MarginKind::Relative, c.margin_detail, sampled.scales[k], true,
                        !coarser_arm_resolves(*sampling_, sampled.scales[k])});
  const std::vector<MetricInfo> bands = scale_band_metrics(sampled, *sampling_, "d", c.margin_spectrum);
  metrics_.insert(metrics_.end(), bands.begin(), bands.end());
  if (sampled.scales.empty()) return;
  spectrum_ = std::make_unique<SmoothingSpectrum>(sampling_->domain(), sampled.scales);
  scale_bands_ = true;
}

ComparisonMetrics::ComparisonMetrics(const PreparedSurface& surface, const Scene& scene, ArmsShare share)
    : domain_(surface.domain), settings_(scene.comparison) {
  const ComparisonSettings& c = settings_;
  const double d = scene.agent_model().parameters[Param::sensor_distance];
  // The coarsest scale the pattern has: spectral bands above it see only how the network's cells
  // happen to be laid out on the surface, which is metastable and differs from seed to seed by as
  // much as a third, so no affordable number of seeds decides them.
  const double pattern_scale = kCoarsestDetailScale * d;
  const bool same_discretisation = share.discretisation;

  // mean / U: the model's one analytic answer (Eq. 5); a backend that loses or invents mass fails
  // here before anything else.
  metrics_.push_back({"mean_over_U", MarginKind::Absolute, c.margin_mean});
  // Coverage above 0.5, 1 and 2 U: how the mass is distributed between strands and background,
  // whatever the pattern's geometry; cheap, dimensionless and steady from seed to seed.
  for (const char* name : {"coverage_0.5U", "coverage_1U", "coverage_2U"})
    metrics_.push_back({name, MarginKind::Absolute, c.margin_coverage});

  // Harmonic bands (common/harness/harmonic_bands.hpp: equal mode counts, whole eigenspaces): only the
  // modes at the pattern's scale or finer (wavelength 2 pi / sqrt(lambda) at most 4 d), where they
  // add how the power is spread over the scales the detail energies summarise. Without enough such
  // modes among the computed eigenpairs, no bands.
  if (!same_discretisation) {
    left_out_.push_back("harmonic bands: the arms run on different triangulations, whose eigenbases differ");
  } else {
    eigenpairs_ = smallest_eigenpairs(domain_, settings_.eigenpairs, true);
    const Eigen::VectorXd& lambda = eigenpairs_.values;
    const int computed = static_cast<int>(lambda.size());
    const double lambda_max = computed > 0 ? lambda.maxCoeff() : 0.0;
    const double lambda_pattern = (2.0 * kPi / pattern_scale) * (2.0 * kPi / pattern_scale);
    const HarmonicBandAssignment assignment = assign_harmonic_bands(lambda, lambda_pattern, c.spectrum_bands);
    if (assignment.bands < 1) {
      // Weyl's law, N(lambda) ~ area lambda / (4 pi): the modes above the pattern's scale, plus one band.
      const double needed = domain_.total_area * lambda_pattern / (4.0 * kPi) + kMinModesPerBand + 1;
      const double shortest = lambda_max > 0.0 ? 2.0 * kPi / std::sqrt(lambda_max) : INFINITY;
      left_out_.push_back("harmonic bands: " + std::to_string(assignment.usable) + " of the " + std::to_string(computed) +
                          " eigenpairs (shortest wavelength " + metres(shortest) + ") lie at the pattern's scale 4 d = " +
                          metres(pattern_scale) + " or finer, fewer than the " + std::to_string(kMinModesPerBand) +
                          " a band needs (compare_eigenpairs of about " +
                          std::to_string(static_cast<long long>(std::ceil(needed))) + " would give one)");
    } else {
      harmonic_band_of_mode_ = assignment.band_of_mode;
      for (int b = 1; b <= assignment.bands; ++b)
        metrics_.push_back({"harmonic_band_" + std::to_string(b), MarginKind::Relative, c.margin_spectrum, pattern_scale});
      harmonic_bands_ = assignment.bands;
    }
  }

  // Detail energies at 1/4 .. 4 sensor distances (scene value; maps would use their mean): they see
  // the pattern at its own scale on any surface, with any number of eigenpairs, and average over
  // many of the pattern's cells, so they vary little from seed to seed. On one triangulation they are
  // measured on it; between two, on the common sampling (ArmsShare), with band powers between
  // consecutive scales as the spectrum.
  if (same_discretisation) {
    std::vector<double> scales;
    for (double multiple : kDetailScales) {
      scales.push_back(multiple * d);
      metrics_.push_back({detail_name(multiple), MarginKind::Relative, c.margin_detail, multiple * d});
    }
    spectrum_ = std::make_unique<SmoothingSpectrum>(domain_, scales);
  } else {
    add_sampled_metrics(surface, d, share);
  }

  // Radial bands on flat domains: the power spectrum on a grid independent of the triangulation.
  // In the set under the same rule as the harmonic bands: only when the grid resolves the pattern's
  // scale (side / (grid / 2) at most 4 d).
  try {
    plane_xy_ = planar_vertex_coordinates(domain_, surface.simulated);
    flat_ = true;
  } catch (const InputError&) {
    flat_ = false;  // curved: the manifold harmonics are the spectrum
  }
  if (flat_) {
    Eigen::Vector2d low = plane_xy_.front(), high = plane_xy_.front();
    for (const Eigen::Vector2d& p : plane_xy_) low = low.cwiseMin(p), high = high.cwiseMax(p);
    const double finest = (high - low).maxCoeff() / (grid_size_ / 2);
    if (finest > pattern_scale) {
      left_out_.push_back("radial bands: the " + std::to_string(grid_size_) + "-cell grid resolves " +
                          metres(finest) + ", coarser than the pattern's scale 4 d = " + metres(pattern_scale));
    } else {
      radial_bands_ = c.spectrum_bands;
      for (int b = 1; b <= radial_bands_; ++b)
        metrics_.push_back({"radial_band_" + std::to_string(b), MarginKind::Relative, c.margin_spectrum, pattern_scale});
    }
  }

  // Agent-density dispersion: whether the agents cluster on the strands as they should. It is the
  // one metric of the agents rather than the field, so a fault that moves agents without yet
  // changing the field shows here first. Its shot-noise floor (F - 1) / N depends on the faces and
  // the agent count, so it compares arms on one discretisation only.
  agent_density_ = same_discretisation;
  if (agent_density_)
    metrics_.push_back({"agent_density", MarginKind::Relative, c.margin_density});
  else
    left_out_.push_back("agent_density: its shot-noise floor (F - 1) / N differs between the arms' discretisations");
}

std::vector<double> ComparisonMetrics::snapshot(const SimulationBackend& sim, double U) const {
  std::vector<double> m;
  m.reserve(metrics_.size());
  const FieldStatistics stats = sim.field_statistics(U);
  m.push_back(stats.mean / U);
  for (double coverage : stats.coverage) m.push_back(coverage);

  const IntrinsicVertexData<double> field = sim.field_values();
  // Band power: sum of c_k^2 over the band's modes / (area * mean^2), dimensionless (as in
  // spectral_metrics.hpp).
  const double mean = stats.mean;
  if (harmonic_bands_ > 0) {
    const Eigen::VectorXd c = manifold_harmonic_coefficients(eigenpairs_, domain_.vertex_mass, field);
    std::vector<double> power(static_cast<size_t>(harmonic_bands_), 0.0);
    for (int k = 0; k < c.size(); ++k)
      if (harmonic_band_of_mode_[static_cast<size_t>(k)] >= 0)
        power[static_cast<size_t>(harmonic_band_of_mode_[static_cast<size_t>(k)])] += c[k] * c[k];
    for (double p : power) m.push_back(mean > 0.0 ? p / (domain_.total_area * mean * mean) : 0.0);
  }

  if (spectrum_) {
    Eigen::VectorXd u(domain_.vertex_count);
    for (int i = 0; i < domain_.vertex_count; ++i) u[i] = field[static_cast<size_t>(i)];
    SmoothingSpectrum::Powers powers;
    if (!sampling_) {
      powers = spectrum_->of(u, mean > 0.0 ? domain_.total_area * mean * mean : 0.0);
    } else {
      const Eigen::VectorXd sampled = CommonSampling::read(to_samples_, u);
      const SurfaceDomain& samples = sampling_->domain();
      double weighted = 0.0;
      for (int i = 0; i < samples.vertex_count; ++i) weighted += samples.vertex_mass[static_cast<size_t>(i)] * sampled[i];
      const double sampled_mean = weighted / samples.total_area;
      powers = spectrum_->of(sampled, sampled_mean > 0.0 ? samples.total_area * sampled_mean * sampled_mean : 0.0);
    }
    m.insert(m.end(), powers.detail.begin(), powers.detail.end());
    if (scale_bands_) m.insert(m.end(), powers.band.begin(), powers.band.end());
  }

  if (radial_bands_ > 0) {
    // Radii 1 .. grid/2 (whole annuli) in equal bands; radius 0 is the mean, left out.
    const RadialSpectrum spectrum = radial_power_spectrum(plane_xy_, domain_.face_vertices, field, grid_size_);
    const int top = grid_size_ / 2;
    std::vector<double> band(static_cast<size_t>(radial_bands_), 0.0);
    for (int r = 1; r <= top; ++r) {
      const int b = std::min(radial_bands_ - 1, (r - 1) * radial_bands_ / top);
      band[static_cast<size_t>(b)] += spectrum.power[static_cast<size_t>(r)] * spectrum.count[static_cast<size_t>(r)];
    }
    for (double p : band) m.push_back(p);
  }

  if (agent_density_) m.push_back(agent_density_dispersion(sim.agent_faces(), domain_.face_area).dispersion);
  return m;
}

std::vector<double> ComparisonMetrics::measure_seed(SimulationBackend& sim, const Scene& scene, double steady_mean_over_U,
                                                     IntrinsicVertexData<double>* final_field) const {
  // Run length, time step and U from the measured arm's own scene: an arm that shares these metrics
  // with another of a different time step must still run the same SIMULATED time (with the other
  // arm's dt it ran burn_in and duration scaled by the ratio of the steps).
  const ComparisonSettings& run = scene.comparison;
  const double U = uniform_steady_state(scene, domain_.total_area);
  const auto steps_for = [&](double seconds) { return std::max<long long>(0, std::llround(seconds / scene.time_step)); };
  const long long burn_in = steps_for(run.burn_in);
  const long long every = std::max<long long>(1, steps_for(run.sample_interval));
  const long long samples = std::max<long long>(1, steps_for(run.duration) / every);
  // The field starts at its steady mean (U, or the time-discrete model's where that differs:
  // common/model/discrete_steady_state.hpp), so the burn-in only has to let the pattern form.
  sim.fill_field(steady_mean_over_U == 1.0 ? U : steady_mean_over_U * U);
  sim.run(burn_in);
  std::vector<double> sum(metrics_.size(), 0.0);
  for (long long s = 0; s < samples; ++s) {
    sim.run(every);
    const std::vector<double> m = snapshot(sim, U);
    for (size_t i = 0; i < m.size(); ++i) sum[i] += m[i];
  }
  for (double& x : sum) x /= static_cast<double>(samples);
  if (final_field) *final_field = sim.field_values();
  return sum;
}

}  // namespace physarum
