#include "common/harness/reaction_diffusion_metrics.hpp"

#include "common/base/errors.hpp"
#include "common/base/number_format.hpp"
#include "common/harness/harmonic_bands.hpp"
#include "common/reaction_diffusion/reaction_formula.hpp"
#include "common/harness/spectral_metrics.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>

namespace physarum {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string metres(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g m", v);
  return text;
}

double trace(const CsrMatrix& m) {
  double t = 0.0;
  for (int r = 0; r < m.rows; ++r)
    for (int k = m.row_start[static_cast<size_t>(r)]; k < m.row_start[static_cast<size_t>(r) + 1]; ++k)
      if (m.column[static_cast<size_t>(k)] == r) t += m.value[static_cast<size_t>(k)];
  return t;
}

struct Moments {
  double mean = 0.0;
  double variance = 0.0;
};

Moments moments(const IntrinsicVertexData<double>& u, const IntrinsicVertexData<double>& mass, double area) {
  Moments m;
  for (size_t i = 0; i < u.size(); ++i) m.mean += mass[i] * u[i];
  m.mean /= area;
  for (size_t i = 0; i < u.size(); ++i) m.variance += mass[i] * (u[i] - m.mean) * (u[i] - m.mean);
  m.variance /= area;
  return m;
}

}  // namespace

double reaction_diffusion_pattern_scale(const ReactionDiffusionSystem& system, const SurfaceDomain& domain,
                                        const std::vector<double>& state) {
  const size_t n = system.morphogens.size();
  if (state.size() != n || system.reaction.size() != n || system.stiffness.size() != n)
    throw InputError("pattern scale: " + std::to_string(state.size()) + " state values for " + std::to_string(n) +
                     " morphogens");
  const double laplacian_trace = trace(domain.laplacian);
  double d_max = 0.0;
  for (const CsrMatrix& k : system.stiffness) d_max = std::max(d_max, trace(k) / laplacian_trace);

  // The formulas over (morphogens, coefficients), the coefficients at their area-weighted means.
  std::vector<std::string> names = system.morphogens;
  names.insert(names.end(), system.coefficient_names.begin(), system.coefficient_names.end());
  std::vector<double> point = state;
  double area = 0.0;
  for (double m : system.mass) area += m;
  for (const IntrinsicVertexData<double>& c : system.coefficients) {
    double mean = 0.0;
    for (size_t i = 0; i < c.size(); ++i) mean += system.mass[i] * c[i];
    point.push_back(mean / area);
  }
  Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (size_t r = 0; r < n; ++r) {
    const ReactionFormula formula(system.reaction[r], names, "pattern scale: reaction of '" + system.morphogens[r] + "'");
    for (size_t c = 0; c < n; ++c) {
      // Central differences, a step of 1e-6 of the value's size: the formulas are smooth
      // polynomials and rationals, so the error (1e-12 relative) is far below what matters here.
      const double h = 1e-6 * std::max(1.0, std::abs(state[c]));
      std::vector<double> up = point, down = point;
      up[c] += h;
      down[c] -= h;
      jacobian(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) =
          (formula.evaluate(up) - formula.evaluate(down)) / (2.0 * h);
    }
  }
  const double rate = Eigen::EigenSolver<Eigen::MatrixXd>(jacobian, false).eigenvalues().cwiseAbs().maxCoeff();
  if (!(d_max > 0.0) || !(rate > 0.0) || !std::isfinite(rate)) return std::numeric_limits<double>::infinity();
  return 2.0 * kPi * std::sqrt(d_max / rate);
}

void ReactionDiffusionMetrics::add_scale_bands(const PreparedSurface& surface, const ArmsShare& share,
                                               const ComparisonSettings& c) {
  if (!share.sampling) {
    left_out_.push_back("scale bands: " + share.no_sampling + ", so there is no common sampling to measure them on");
    return;
  }
  sampling_ = share.sampling;
  to_samples_ = sampling_->from(surface);
  const SampledScales sampled = sampled_scales(
      *sampling_, std::vector<double>(std::begin(kScaleBandEdges), std::end(kScaleBandEdges)), pattern_scale_,
      [](double multiple) { return "scale bands at " + format_number(multiple) + " pattern scales"; }, left_out_);
  const std::vector<MetricInfo> bands = scale_band_metrics(sampled, *sampling_, "l", c.margin_spectrum);
  metrics_.insert(metrics_.end(), bands.begin(), bands.end());
  if (!bands.empty()) spectrum_ = std::make_unique<SmoothingSpectrum>(sampling_->domain(), sampled.scales);
}

ReactionDiffusionMetrics::ReactionDiffusionMetrics(const PreparedSurface& surface, const Scene& scene,
                                                   double pattern_scale, ArmsShare share)
    : domain_(surface.domain), pattern_scale_(pattern_scale) {
  if (!scene.reaction_diffusion())
    throw InputError(scene.source + ": reaction-diffusion metrics for a scene that is not a reaction-diffusion system");
  const ReactionDiffusionSpec& spec = *scene.reaction_diffusion();
  const ComparisonSettings& c = scene.comparison;
  morphogens_ = static_cast<int>(spec.morphogens.size());
  preview_ = spec.morphogen_index(spec.preview_morphogen);
  if (preview_ < 0) throw InputError(scene.source + ": preview_morphogen '" + spec.preview_morphogen + "' is no morphogen");
  const std::string& p = spec.preview_morphogen;

  for (const MorphogenSpec& m : spec.morphogens) metrics_.push_back({"mean_" + m.name, MarginKind::Relative, c.margin_mean});
  for (const MorphogenSpec& m : spec.morphogens) metrics_.push_back({"cv2_" + m.name, MarginKind::Relative, c.margin_detail});
  for (double f : kCoverageRangeFractions) {
    char name[64];
    std::snprintf(name, sizeof name, "coverage_%s_%grange", p.c_str(), f);
    metrics_.push_back({name, MarginKind::Absolute, c.margin_coverage});
  }

  const double coarsest = kCoarsestBandScale * pattern_scale;
  if (!std::isfinite(pattern_scale)) {
    left_out_.push_back("harmonic and radial bands: the system has no pattern scale (nothing diffuses, or the kinetics "
                        "have no rate at the initial state)");
    return;
  }

  // Harmonic band shares: modes at the coarsest pattern scale or finer, equal mode counts, whole
  // eigenspaces (common/harness/harmonic_bands.hpp). Only on one triangulation: two have different bases.
  if (!share.discretisation) {
    left_out_.push_back("harmonic bands: the arms run on different triangulations, whose eigenbases differ; scale "
                        "bands on their common sampling take their place");
    add_scale_bands(surface, share, c);
  } else {
    eigenpairs_ = smallest_eigenpairs(domain_, c.eigenpairs, true);
    const Eigen::VectorXd& lambda = eigenpairs_.values;
    const double lambda_pattern = (2.0 * kPi / coarsest) * (2.0 * kPi / coarsest);
    const HarmonicBandAssignment assignment = assign_harmonic_bands(lambda, lambda_pattern, c.spectrum_bands);
    if (assignment.bands < 1) {
      // Weyl's law, N(lambda) ~ area lambda / (4 pi): the modes coarser than the pattern, plus one band.
      const double needed = domain_.total_area * lambda_pattern / (4.0 * kPi) + kMinModesPerBand + 1;
      const double lambda_max = lambda.size() > 0 ? lambda.maxCoeff() : 0.0;
      const double shortest = lambda_max > 0.0 ? 2.0 * kPi / std::sqrt(lambda_max) : INFINITY;
      left_out_.push_back("harmonic bands: " + std::to_string(assignment.usable) + " of the " +
                          std::to_string(lambda.size()) + " eigenpairs (shortest wavelength " + metres(shortest) +
                          ") lie at the pattern's scale " + metres(coarsest) + " or finer, fewer than the " +
                          std::to_string(kMinModesPerBand) + " a band needs (compare_eigenpairs of about " +
                          std::to_string(static_cast<long long>(std::ceil(needed))) +
                          " would give one); scale bands on the surface's own vertices take their place");
      // The smoother needs no eigenbasis: the surface sampled at its own vertices (the agent model's
      // detail energies are measured the same way). The surface outlives these metrics (domain_).
      const std::shared_ptr<const PreparedSurface> own(std::shared_ptr<const PreparedSurface>(), &surface);
      ArmsShare on_own_vertices = share;
      on_own_vertices.sampling = std::make_shared<const CommonSampling>(own, own);
      add_scale_bands(surface, on_own_vertices, c);
    } else {
      harmonic_band_of_mode_ = assignment.band_of_mode;
      harmonic_bands_ = assignment.bands;
      for (int b = 1; b <= harmonic_bands_; ++b)
        metrics_.push_back({"harmonic_band_" + std::to_string(b), MarginKind::Relative, c.margin_spectrum, coarsest});
    }
  }

  // Radial band shares on flat domains: a spectrum on a grid, independent of the triangulation (so
  // also between two triangulations), where the grid resolves the pattern's scale.
  try {
    plane_xy_ = planar_vertex_coordinates(domain_, surface.simulated);
  } catch (const InputError&) {
    plane_xy_.clear();  // curved: the manifold harmonics are the spectrum
  }
  if (!plane_xy_.empty()) {
    Eigen::Vector2d low = plane_xy_.front(), high = plane_xy_.front();
    for (const Eigen::Vector2d& q : plane_xy_) low = low.cwiseMin(q), high = high.cwiseMax(q);
    const double side = (high - low).maxCoeff();
    const int top = grid_size_ / 2;
    const double finest = side / top;
    radial_first_ = std::max(1, static_cast<int>(std::ceil(side / coarsest)));
    if (finest > pattern_scale || radial_first_ > top) {
      left_out_.push_back("radial bands: the " + std::to_string(grid_size_) + "-cell grid resolves " + metres(finest) +
                          ", coarser than the pattern's scale " + metres(pattern_scale));
    } else {
      radial_bands_ = std::min(c.spectrum_bands, top - radial_first_ + 1);
      for (int b = 1; b <= radial_bands_; ++b)
        metrics_.push_back({"radial_band_" + std::to_string(b), MarginKind::Relative, c.margin_spectrum, coarsest});
    }
  }
}

std::vector<double> ReactionDiffusionMetrics::snapshot(const std::vector<IntrinsicVertexData<double>>& layers) const {
  if (static_cast<int>(layers.size()) != morphogens_)
    throw InputError("reaction-diffusion metrics: " + std::to_string(layers.size()) + " layers for " +
                     std::to_string(morphogens_) + " morphogens");
  const IntrinsicVertexData<double>& mass = domain_.vertex_mass;
  const double area = domain_.total_area;
  std::vector<double> m;
  m.reserve(metrics_.size());
  std::vector<Moments> mo;
  for (const auto& u : layers) {
    if (u.size() != mass.size())
      throw InputError("reaction-diffusion metrics: " + std::to_string(u.size()) + " values for " +
                       std::to_string(mass.size()) + " vertices");
    mo.push_back(moments(u, mass, area));
  }
  for (const Moments& x : mo) m.push_back(x.mean);
  // A mean of 0 (a morphogen that died out) has no contrast to speak of: 0, not a division by 0.
  for (const Moments& x : mo) m.push_back(x.mean != 0.0 ? x.variance / (x.mean * x.mean) : 0.0);

  const IntrinsicVertexData<double>& u = layers[static_cast<size_t>(preview_)];
  const auto [low, high] = std::minmax_element(u.begin(), u.end());
  for (double f : kCoverageRangeFractions) {
    // A uniform field has no range: nothing lies above any fraction of it.
    if (!(*high > *low)) {
      m.push_back(0.0);
      continue;
    }
    const double threshold = *low + f * (*high - *low);
    double above = 0.0;
    for (size_t i = 0; i < u.size(); ++i)
      if (u[i] > threshold) above += mass[i];
    m.push_back(above / area);
  }

  const double variance = mo[static_cast<size_t>(preview_)].variance;
  if (harmonic_bands_ > 0) {
    // Parseval: sum over ALL non-constant modes of c_k^2 is area x variance, so c_k^2 / (area x
    // variance) summed over a band is that band's share of the variance.
    const Eigen::VectorXd coefficients = manifold_harmonic_coefficients(eigenpairs_, mass, u);
    std::vector<double> power(static_cast<size_t>(harmonic_bands_), 0.0);
    for (Eigen::Index k = 0; k < coefficients.size(); ++k) {
      const int band = harmonic_band_of_mode_[static_cast<size_t>(k)];
      if (band >= 0) power[static_cast<size_t>(band)] += coefficients[k] * coefficients[k];
    }
    for (double p : power) m.push_back(variance > 0.0 ? p / (area * variance) : 0.0);
  }

  if (spectrum_) {
    // Shares of the variance on the common sampling, between consecutive scales.
    Eigen::VectorXd field(static_cast<Eigen::Index>(u.size()));
    for (size_t i = 0; i < u.size(); ++i) field[static_cast<Eigen::Index>(i)] = u[i];
    const Eigen::VectorXd sampled = CommonSampling::read(to_samples_, field);
    const SurfaceDomain& samples = sampling_->domain();
    double mean = 0.0, spread = 0.0;
    for (int i = 0; i < samples.vertex_count; ++i) mean += samples.vertex_mass[static_cast<size_t>(i)] * sampled[i];
    mean /= samples.total_area;
    for (int i = 0; i < samples.vertex_count; ++i)
      spread += samples.vertex_mass[static_cast<size_t>(i)] * (sampled[i] - mean) * (sampled[i] - mean);
    const SmoothingSpectrum::Powers powers = spectrum_->of(sampled, spread);
    m.insert(m.end(), powers.band.begin(), powers.band.end());
  }

  if (radial_bands_ > 0) {
    // The spectrum of the field shifted to a positive mean (radial_power_spectrum normalises by the
    // mean): a constant shift changes only radius 0, and the normalisation cancels in the shares.
    IntrinsicVertexData<double> shifted = u;
    for (double& x : shifted) x += 1.0 - *low;
    const RadialSpectrum spectrum = radial_power_spectrum(plane_xy_, domain_.face_vertices, shifted, grid_size_);
    double total = 0.0;
    for (size_t r = 1; r < spectrum.power.size(); ++r) total += spectrum.power[r] * spectrum.count[r];
    const int top = grid_size_ / 2, radii = top - radial_first_ + 1;
    std::vector<double> band(static_cast<size_t>(radial_bands_), 0.0);
    for (int r = radial_first_; r <= top; ++r) {
      const int b = std::min(radial_bands_ - 1, (r - radial_first_) * radial_bands_ / radii);
      band[static_cast<size_t>(b)] += spectrum.power[static_cast<size_t>(r)] * spectrum.count[static_cast<size_t>(r)];
    }
    for (double p : band) m.push_back(total > 0.0 ? p / total : 0.0);
  }
  return m;
}

std::vector<double> ReactionDiffusionMetrics::measure_seed(SimulationBackend& sim, const Scene& scene,
                                                           IntrinsicVertexData<double>* final_field) const {
  const ComparisonSettings& run = scene.comparison;
  if (!(run.duration > 0.0))  // common/scene/scene.cpp: a reaction-diffusion scene without any run length
    throw InputError(scene.source + ": a reaction-diffusion scene needs a run length for physarum compare: 'steps' "
                                    "or 'sim_time' (the comparison then averages the second half), or "
                                    "'compare_burn_in' and 'compare_duration'");
  const auto steps_for = [&](double seconds) { return std::max<long long>(0, std::llround(seconds / scene.time_step)); };
  const long long burn_in = steps_for(run.burn_in);
  const long long every = std::max<long long>(1, steps_for(run.sample_interval));
  const long long samples = std::max<long long>(1, steps_for(run.duration) / every);
  sim.run(burn_in);
  std::vector<double> sum(metrics_.size(), 0.0);
  std::vector<IntrinsicVertexData<double>> layers(static_cast<size_t>(morphogens_));
  for (long long s = 0; s < samples; ++s) {
    sim.run(every);
    for (int k = 0; k < morphogens_; ++k) {
      layers[static_cast<size_t>(k)] = sim.field_values(k);
      for (double x : layers[static_cast<size_t>(k)])
        if (!std::isfinite(x))
          throw InputError(scene.source + ": seed " + std::to_string(scene.seed) + " on the " + sim.backend_name() +
                           " backend diverged (morphogen '" + scene.reaction_diffusion()->morphogens[static_cast<size_t>(k)].name +
                           "' not finite at t = " + std::to_string(sim.time()) +
                           " s); a smaller time_step, or \"integrator\": \"imex\"");
    }
    const std::vector<double> m = snapshot(layers);
    for (size_t i = 0; i < m.size(); ++i) sum[i] += m[i];
  }
  for (double& x : sum) x /= static_cast<double>(samples);
  if (final_field) *final_field = layers[static_cast<size_t>(preview_)];
  return sum;
}

}  // namespace physarum
