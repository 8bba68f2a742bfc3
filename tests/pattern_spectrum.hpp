#pragma once
// The dominant wavenumber of a grown pattern, for the reaction-diffusion known-answer tests: where
// the power spectrum of a field peaks, estimated below the spectrum's bin width, on a flat surface
// (the radially averaged 2D FFT spectrum of common/harness/spectral_metrics.hpp) and on a sphere (the power
// per spherical-harmonic degree, projected here on Y_lm from Boost.Math's associated Legendre
// functions, so the reference owes nothing to the discrete Laplacian under test). Also the
// "connectivity Laplacian" a graph-based tool diffuses with, to show what the cotan Laplacian buys.
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/harness/spectral_metrics.hpp"
#include "common/surface/surface_domain.hpp"

#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/special_functions/legendre.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace physarum::testing {

// The peak of a spectrum sampled at bins 0, 1, ... with power[b] at wavenumber position[b]: the
// bin of largest power among [first, last], refined to the power-weighted centroid of `position`
// over that bin and its two neighbours on each side. The centroid is what a sub-bin estimate needs:
// a pattern whose wavenumber falls between two bins shares its power between them.
struct SpectralPeak {
  int bin = 0;            // the largest bin
  double position = 0.0;  // the sub-bin estimate
};

inline SpectralPeak spectral_peak(const std::vector<double>& power, const std::vector<double>& position, int first, int last) {
  last = std::min(last, static_cast<int>(power.size()) - 1);
  if (first < 0 || first > last) throw std::invalid_argument("spectral_peak: empty range");
  SpectralPeak peak;
  peak.bin = first;
  for (int b = first; b <= last; ++b)
    if (power[static_cast<size_t>(b)] > power[static_cast<size_t>(peak.bin)]) peak.bin = b;
  double weight = 0.0, sum = 0.0;
  for (int b = std::max(first, peak.bin - 2); b <= std::min(last, peak.bin + 2); ++b) {
    weight += power[static_cast<size_t>(b)];
    sum += power[static_cast<size_t>(b)] * position[static_cast<size_t>(b)];
  }
  peak.position = sum / weight;
  return peak;
}

// ---- flat surfaces ----

// The peak of the radially averaged power spectrum (mean power per annulus: white noise is flat in
// it, so a peak is the pattern's, not the annulus' size) of a field on a flat surface, as a
// wavenumber in rad/m. `grid` cells per side; annuli below `first_radius` cycles per side are left
// out (the largest scales carry the initial condition's layout, not the pattern's period).
struct RadialPeak {
  SpectralPeak peak;          // in cycles per side
  double side = 0.0;          // m
  double wavenumber = 0.0;    // rad/m: 2 pi peak.position / side
  RadialSpectrum spectrum;
};

inline RadialPeak radial_peak(const PreparedSurface& surface, const IntrinsicVertexData<double>& field, int grid,
                              int first_radius = 2) {
  RadialPeak r;
  r.spectrum = radial_power_spectrum(planar_vertex_coordinates(surface.domain, surface.simulated),
                                     surface.domain.face_vertices, field, grid);
  std::vector<double> radius(r.spectrum.power.size());
  for (size_t b = 0; b < radius.size(); ++b) radius[b] = static_cast<double>(b);
  r.peak = spectral_peak(r.spectrum.power, radius, first_radius, grid / 2);
  r.side = r.spectrum.side;
  r.wavenumber = 2.0 * std::numbers::pi * r.peak.position / r.side;
  return r;
}

// ---- spheres ----

// Mean power per spherical-harmonic degree l = 0 .. max_degree of a field on a sphere centred at the
// origin: P(l) = sum_m |c_lm|^2 / (2l + 1), c_lm = sum_i mass_i u_i conj(Y_lm(theta_i, phi_i)) (the
// lumped-mass quadrature of the projection), the field's mean removed. White noise gives a flat
// P(l); an eigenfunction of degree L of the Laplace-Beltrami operator puts all its power in P(L).
inline std::vector<double> spherical_degree_power(const std::vector<Eigen::Vector3d>& position,
                                                  const IntrinsicVertexData<double>& mass,
                                                  const IntrinsicVertexData<double>& field, int max_degree) {
  double area = 0.0, mean = 0.0;
  for (size_t i = 0; i < field.size(); ++i) area += mass[i], mean += mass[i] * field[i];
  mean /= area;
  const size_t degrees = static_cast<size_t>(max_degree) + 1;
  // Y_lm = N_lm P_l^m(cos theta) e^{i m phi} with N_lm = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!);
  // P_l^m over l by Boost's three-term recurrence (legendre_next) from P_m^m, so each vertex costs
  // O(max_degree^2) rather than a fresh Legendre evaluation per (l, m).
  std::vector<std::complex<double>> c(degrees * degrees, 0.0);  // c[l * degrees + m], m <= l
  std::vector<double> norm(degrees * degrees, 0.0);
  for (unsigned l = 0; l < degrees; ++l)
    for (unsigned m = 0; m <= l; ++m)
      norm[l * degrees + m] = std::sqrt((2.0 * l + 1.0) / (4.0 * std::numbers::pi) *
                                        boost::math::tgamma_ratio(static_cast<double>(l - m + 1), static_cast<double>(l + m + 1)));
  for (size_t i = 0; i < field.size(); ++i) {
    const Eigen::Vector3d& p = position[i];
    const double x = std::clamp(p.z() / p.norm(), -1.0, 1.0), phi = std::atan2(p.y(), p.x());
    const double w = mass[i] * (field[i] - mean);
    for (unsigned m = 0; m <= static_cast<unsigned>(max_degree); ++m) {
      const std::complex<double> rotation = w * std::polar(1.0, -static_cast<double>(m) * phi);
      double previous = 0.0, current = boost::math::legendre_p(static_cast<int>(m), static_cast<int>(m), x);
      for (unsigned l = m; l <= static_cast<unsigned>(max_degree); ++l) {
        c[l * degrees + m] += rotation * (norm[l * degrees + m] * current);
        const double next = boost::math::legendre_next(l, m, x, current, previous);
        previous = current;
        current = next;
      }
    }
  }
  std::vector<double> power(degrees, 0.0);
  for (size_t l = 0; l < degrees; ++l) {
    // A real field has c_{l,-m} = (-1)^m conj(c_lm): the negative orders add what the positive do.
    double sum = std::norm(c[l * degrees]);
    for (size_t m = 1; m <= l; ++m) sum += 2.0 * std::norm(c[l * degrees + m]);
    power[l] = sum / (2.0 * static_cast<double>(l) + 1.0);
  }
  return power;
}

// The peak of spherical_degree_power over degrees [first, max_degree], as a wavenumber in rad/m:
// degree l of a sphere of radius R is the Laplace-Beltrami eigenvalue l (l + 1) / R^2, so its
// wavenumber is sqrt(l (l + 1)) / R (the centroid is taken over those wavenumbers).
struct SphericalPeak {
  SpectralPeak peak;        // bin = degree; position in rad/m
  double wavenumber = 0.0;  // rad/m (= peak.position)
  std::vector<double> power;
};

inline SphericalPeak spherical_peak(const std::vector<Eigen::Vector3d>& position, const IntrinsicVertexData<double>& mass,
                                    const IntrinsicVertexData<double>& field, double radius, int max_degree, int first = 1) {
  SphericalPeak s;
  s.power = spherical_degree_power(position, mass, field, max_degree);
  std::vector<double> wavenumber(s.power.size());
  for (size_t l = 0; l < wavenumber.size(); ++l) wavenumber[l] = std::sqrt(static_cast<double>(l * (l + 1))) / radius;
  s.peak = spectral_peak(s.power, wavenumber, first, max_degree);
  s.wavenumber = s.peak.position;
  return s;
}

// ---- the connectivity Laplacian ----

// Replaces the system's diffusion by the graph ("umbrella") Laplacian that connectivity-based tools
// use: du_i/dt = D scale sum_{j ~ i} (u_j - u_i), every vertex one cell (mass 1), every edge of the
// triangulation weight 1 whatever its length or angles. `scale` (1/m^2) stands for the tool's fixed
// conversion from its per-edge rates to the surface; `rate` is each morphogen's diffusion rate.
inline void use_connectivity_laplacian(ReactionDiffusionSystem& system, const SurfaceDomain& domain,
                                       const std::vector<double>& rate, double scale) {
  const CsrMatrix& pattern = domain.laplacian;
  for (size_t m = 0; m < system.stiffness.size(); ++m) {
    CsrMatrix k = pattern;
    for (int i = 0; i < pattern.rows; ++i) {
      int degree = 0, diagonal = -1;
      for (int e = pattern.row_start[static_cast<size_t>(i)]; e < pattern.row_start[static_cast<size_t>(i) + 1]; ++e) {
        if (pattern.column[static_cast<size_t>(e)] == i) {
          diagonal = e;
          continue;
        }
        k.value[static_cast<size_t>(e)] = -rate[m] * scale;
        ++degree;
      }
      if (diagonal < 0) throw std::logic_error("use_connectivity_laplacian: a row without its diagonal");
      k.value[static_cast<size_t>(diagonal)] = rate[m] * scale * degree;
    }
    system.stiffness[m] = std::move(k);
  }
  system.mass.assign(system.mass.size(), 1.0);
}

// The `scale` that makes the connectivity Laplacian agree with the cotan one on average over this
// domain (equal sums of the diagonals of M^-1 L and of the graph Laplacian): the calibration a user
// of such a tool does once, on the mesh in front of them.
inline double connectivity_scale_matching(const SurfaceDomain& domain) {
  double cotan = 0.0, graph = 0.0;
  const CsrMatrix& l = domain.laplacian;
  for (int i = 0; i < l.rows; ++i)
    for (int e = l.row_start[static_cast<size_t>(i)]; e < l.row_start[static_cast<size_t>(i) + 1]; ++e) {
      if (l.column[static_cast<size_t>(e)] == i) cotan += l.value[static_cast<size_t>(e)] / domain.vertex_mass[static_cast<size_t>(i)];
      else graph += 1.0;
    }
  return cotan / graph;
}

}  // namespace physarum::testing
