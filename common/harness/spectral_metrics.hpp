#pragma once
// Per-snapshot pattern metrics for the long-horizon differential harness (its long horizon: independent
// seeds per backend, time-averaged per-seed metrics). Mean and coverage (common/simulation/field_statistics.hpp) only see the
// distribution of values; these see the spatial STRUCTURE of the pattern, which is what a wrong
// sensor angle or a missing boundary reflection changes first:
//
//   * manifold-harmonic band powers: the field projected onto the low eigenvectors of
//     L phi = lambda M phi (the surface's Fourier basis), squared coefficients summed in bands of
//     sqrt(lambda) (sqrt(lambda) is a spatial frequency: on a flat domain phi ~ cos(k x) has
//     lambda = k^2). Works on any surface.
//   * on flat domains, the radially averaged 2D power spectrum of the field resampled on a grid:
//     finer frequency resolution than a few hundred eigenpairs give, and the classic statistic for
//     labyrinth/network patterns.
//   * the dispersion of the agent density over faces.
//
// Every metric is normalised to be dimensionless (divided by the squared mean, or by the mean
// density), so the numbers are comparable across scenes with different deposit rates or areas and
// margins can be stated as plain fractions. Each returns ONE number per band/radius per snapshot;
// the harness time-averages them per seed, and the seed is the unit of replication.
#include "common/surface/eigenvalues.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace physarum {

struct SurfaceDomain;
struct InputMesh;

// ---- manifold-harmonic band powers ---------------------------------------------------------------

// Coefficients c_k = phi_k^T M u of a per-vertex field u on the eigenvectors (M the diagonal lumped
// mass). With M-orthonormal phi_k, sum_k c_k^2 over ALL modes equals u^T M u = integral of u^2.
Eigen::VectorXd manifold_harmonic_coefficients(const Eigenpairs& pairs, const IntrinsicVertexData<double>& mass,
                                               const IntrinsicVertexData<double>& field);

struct ManifoldHarmonicBands {
  // bands + 1 edges in sqrt(lambda): edges[0] = 0, edges[bands] = sqrt(largest eigenvalue given),
  // equal width. Mode k belongs to band floor(sqrt(lambda_k) / width), the top edge to the top band.
  std::vector<double> edges;
  std::vector<double> power;  // per band: sum of c_k^2 over its modes / (total area * mean^2)
  std::vector<int> modes;     // eigenpairs counted in each band
  double mean = 0.0;          // area-weighted mean of the field (the normaliser)
  int constant_modes = 0;     // eigenpairs with lambda ~ 0 (one per connected component), left out
};

// Band powers of `field` over the eigenpairs `pairs` of the domain (smallest_eigenpairs(domain, K)).
//
// The constant modes (lambda <= 1e-8 lambda_max; piecewise constant on several components) carry
// only the mean and are left out, so the powers describe the pattern, not its level. Normalising
// by total area * mean^2 makes them dimensionless and invariant under scaling the field or the
// surface's units: summed over all non-constant modes they would give exactly the area-weighted
// variance over mean^2, the squared coefficient of variation (Parseval), and a band's power is
// that band's share of it. Bands are equal in sqrt(lambda) (wavenumber), like the annuli of the
// radial FFT spectrum. Throws InputError on size mismatches, bands < 1, or a mean <= 0.
ManifoldHarmonicBands manifold_harmonic_band_powers(const SurfaceDomain& domain, const Eigenpairs& pairs,
                                                    const IntrinsicVertexData<double>& field, int bands);

// ---- radially averaged power spectrum on flat domains --------------------------------------------

// 2D coordinates of the domain's vertices in the plane of a FLAT input mesh: each vertex's location
// on the input mesh (face + barycentric) interpolated and expressed in an orthonormal basis of the
// plane (x and y themselves when the plane is z = const). Throws InputError when the input is not
// planar (a vertex more than 1e-6 of the bounding-box diagonal off the plane).
std::vector<Eigen::Vector2d> planar_vertex_coordinates(const SurfaceDomain& domain, const InputMesh& input);

// A per-vertex field sampled at the cell centres of a size x size grid over the SQUARE of side
// max(width, height) centred on the vertices' bounding box (a square, so that one frequency unit is
// the same length in x and y). Sample (i, j) (column i along x, row j along y) is at
// origin + ((i + 1/2) cell, (j + 1/2) cell), value index j * size + i.
struct GridSamples {
  int size = 0;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 0.0;
  std::vector<double> value;  // linear interpolation in the triangle containing the centre; 0 if none
  std::vector<char> covered;  // 1 where a triangle contains the centre
};

// Rasterises by barycentric interpolation per triangle (faces index vertex_xy and field, as
// SurfaceDomain::face_vertices does). Throws InputError on size mismatches or size < 2.
GridSamples rasterize_planar_field(const std::vector<Eigen::Vector2d>& vertex_xy,
                                   const std::vector<std::array<int, 3>>& faces, const IntrinsicVertexData<double>& field,
                                   int size);

struct RadialSpectrum {
  // Radius r collects the frequencies (kx, ky), in cycles per grid side, with round(|k|) = r;
  // r runs from 0 to the corner of the frequency square, so radii above size/2 are partial annuli.
  std::vector<double> power;  // mean over the annulus of |F(k)|^2 / (cells^2 * mean^2)
  std::vector<int> count;     // frequencies in the annulus
  double mean = 0.0;          // mean over the covered cells (the normaliser)
  double side = 0.0;          // grid side length: radius r is the wavelength side / r
};

// The grid's covered samples minus their mean (uncovered cells: 0, i.e. the mean), 2D FFT (Eigen's
// FFT module), |F|^2 normalised by (cells^2 mean^2) and averaged over annuli of integer radius.
// Normalisation, as for the band powers: sum_r power[r] * count[r] is the variance of the grid
// (uncovered cells counting as the mean) over mean^2 (Parseval). Throws InputError when no cell is
// covered or the mean is <= 0.
RadialSpectrum radial_power_spectrum(const GridSamples& grid);
RadialSpectrum radial_power_spectrum(const std::vector<Eigen::Vector2d>& vertex_xy,
                                     const std::vector<std::array<int, 3>>& faces, const IntrinsicVertexData<double>& field,
                                     int size);

// ---- agent density -------------------------------------------------------------------------------

struct AgentDensityDispersion {
  // Area-weighted variance of the per-face agent density divided by the mean density:
  //   D = sum_f (A_f / A) (rho_f / rho_mean - 1)^2,  rho_f = n_f / A_f,  rho_mean = N / A.
  // 0 when agents are spread exactly in proportion to area, (1 - p)/p when all sit on one face of
  // area fraction p. Equal to Pearson's chi-square statistic of the face counts against
  // area-proportional placement, divided by N.
  double dispersion = 0.0;
  // E[D] for N agents placed independently with probability proportional to area: (F - 1) / N.
  // The shot-noise floor; only D well above it means the agents cluster.
  double uniform_expectation = 0.0;
};

// Why this and not a histogram: a coarse partition of an arbitrary surface is not canonical, but the
// domain's own faces are, and both arms of a comparison run on the same domain with the same agent
// count, so the shot-noise floor is the same in both. agent_face holds each agent's face index;
// face_area every face's area (all > 0). Throws InputError on an empty agent list, an index out of
// range or a face area <= 0.
AgentDensityDispersion agent_density_dispersion(const std::vector<int>& agent_face,
                                                const IntrinsicFaceData<double>& face_area);

}  // namespace physarum
