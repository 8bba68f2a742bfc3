// Pattern metrics against answers known without this code: spherical harmonics on the unit sphere
// (x, y, z are l = 1, xy is l = 2, xyz is l = 3; their integrals over the sphere are 4 pi/3,
// 4 pi/15 and 4 pi/105), single eigenvectors, Parseval totals computed directly from the field,
// plane waves on the unit square whose DFT peaks at a known integer wavevector, and agent
// placements whose density variance is worked out by hand.
#include "common/harness/spectral_metrics.hpp"

#include "common/surface/eigenvalues.hpp"
#include "common/base/errors.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/surface/surface_domain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace physarum {
namespace {

constexpr double kPi = std::numbers::pi;

struct SphereFixture {
  InputMesh input = load_mesh("shape:sphere");
  SurfaceDomain domain = build_surface_domain(intrinsic_mesh_from_input(input));
  // l = 0..4: 1 + 3 + 5 + 7 + 9 = 25 modes, sqrt(lambda) ~ 0, 1.41, 2.45, 3.46, 4.47.
  Eigenpairs pairs = smallest_eigenpairs(domain, 25);
};

const SphereFixture& sphere() {
  static const SphereFixture f;
  return f;
}

// The field f(position) at every vertex (for shapes, domain vertex i is input vertex i).
template <class F>
IntrinsicVertexData<double> sample(const SphereFixture& s, F f) {
  IntrinsicVertexData<double> u(s.domain.vertex_count);
  for (int v = 0; v < s.domain.vertex_count; ++v) u[v] = f(s.input.positions[v]);
  return u;
}

// Area-weighted variance / mean^2, straight from the definition.
double squared_cv(const IntrinsicVertexData<double>& u, const IntrinsicVertexData<double>& m) {
  double a = 0, s = 0;
  for (size_t i = 0; i < u.size(); ++i) {
    a += m[i];
    s += m[i] * u[i];
  }
  const double mean = s / a;
  double v = 0;
  for (size_t i = 0; i < u.size(); ++i) v += m[i] * (u[i] - mean) * (u[i] - mean);
  return v / a / (mean * mean);
}

TEST(SpectralMetrics, BandEdgesAreEqualInSqrtLambdaAndTheConstantModeIsLeftOut) {
  const SphereFixture& s = sphere();
  const IntrinsicVertexData<double> constant(s.domain.vertex_count, 3.0);
  const ManifoldHarmonicBands r = manifold_harmonic_band_powers(s.domain, s.pairs, constant, 4);
  ASSERT_EQ(r.edges.size(), 5u);
  EXPECT_EQ(r.edges[0], 0.0);
  EXPECT_NEAR(r.edges[4], std::sqrt(s.pairs.values[24]), 1e-12);
  EXPECT_NEAR(r.edges[4], std::sqrt(20.0), 0.02 * std::sqrt(20.0));  // l = 4
  for (int b = 0; b < 4; ++b) EXPECT_NEAR(r.edges[b + 1] - r.edges[b], r.edges[4] / 4, 1e-12);
  EXPECT_EQ(r.constant_modes, 1);
  EXPECT_NEAR(r.mean, 3.0, 1e-12);
  // Width sqrt(20)/4 = 1.118: l = 1 in band 1, l = 2 in band 2, l = 3 and 4 in band 3, none in band 0.
  EXPECT_EQ(r.modes, (std::vector<int>{0, 3, 5, 16}));
  for (double p : r.power) EXPECT_LT(p, 1e-20);  // a constant has no pattern
}

TEST(SpectralMetrics, OneEigenvectorLandsInItsOwnBandOnly) {
  const SphereFixture& s = sphere();
  for (int k : {2, 6, 12, 20}) {
    // u = 2 + 0.5 phi_k: c_k = 0.5 (phi_k is M-normalised), so its band holds 0.25 / (A * 2^2).
    IntrinsicVertexData<double> u(s.domain.vertex_count);
    for (int v = 0; v < s.domain.vertex_count; ++v) u[v] = 2.0 + 0.5 * s.pairs.vectors(v, k);
    const ManifoldHarmonicBands r = manifold_harmonic_band_powers(s.domain, s.pairs, u, 4);
    const double root = std::sqrt(s.pairs.values[k]);
    for (int b = 0; b < 4; ++b) {
      const bool own = root >= r.edges[b] && (root < r.edges[b + 1] || b == 3);
      if (own)
        EXPECT_NEAR(r.power[b], 0.25 / (s.domain.total_area * 4.0), 1e-12) << "mode " << k << " band " << b;
      else
        EXPECT_LT(r.power[b], 1e-16) << "mode " << k << " band " << b;
    }
  }
}

TEST(SpectralMetrics, SphericalHarmonicsLandInTheBandOfTheirDegree) {
  const SphereFixture& s = sphere();
  // u = 1 + 0.5 z: mean 1, integral of (0.5 z)^2 = 0.25 * 4 pi / 3, over area 4 pi -> 1/12, band 1.
  // u = 1 + x y: integral of x^2 y^2 = 4 pi / 15 -> 1/15, band 2.
  // u = 1 + 2 x y z: integral of 4 x^2 y^2 z^2 = 16 pi / 105 -> 4/105, band 3.
  struct Case {
    IntrinsicVertexData<double> u;
    int band;
    double power;
  };
  const std::vector<Case> cases = {
      {sample(s, [](const Eigen::Vector3d& p) { return 1.0 + 0.5 * p.z(); }), 1, 1.0 / 12.0},
      {sample(s, [](const Eigen::Vector3d& p) { return 1.0 + p.x() * p.y(); }), 2, 1.0 / 15.0},
      {sample(s, [](const Eigen::Vector3d& p) { return 1.0 + 2.0 * p.x() * p.y() * p.z(); }), 3, 4.0 / 105.0},
  };
  for (const Case& c : cases) {
    const ManifoldHarmonicBands r = manifold_harmonic_band_powers(s.domain, s.pairs, c.u, 4);
    for (int b = 0; b < 4; ++b) {
      if (b == c.band)
        EXPECT_NEAR(r.power[b], c.power, 0.02 * c.power) << "band " << b;
      else
        EXPECT_LT(r.power[b], 1e-3 * c.power) << "band " << b << " of a degree-" << c.band << " harmonic";
    }
    // The field lies (nearly) in the span of the 25 modes: all its variance is in the bands.
    double total = 0;
    for (double p : r.power) total += p;
    EXPECT_NEAR(total, squared_cv(c.u, s.domain.vertex_mass), 1e-3 * total);
  }
}

TEST(SpectralMetrics, BandPowersSumToTheSquaredCoefficientOfVariationAndAreScaleFree) {
  const SphereFixture& s = sphere();
  // u = 3 + sum of modes across several bands: Parseval says the bands hold exactly the
  // area-weighted variance / mean^2, computed here from the vertex values directly.
  IntrinsicVertexData<double> u(s.domain.vertex_count, 3.0);
  const double a[] = {0.0, 0.7, 0.0, 0.0, -0.4, 0.0, 0.0, 0.0, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5};
  for (int k = 0; k < 19; ++k)
    for (int v = 0; v < s.domain.vertex_count; ++v) u[v] += a[k] * s.pairs.vectors(v, k);
  const ManifoldHarmonicBands r = manifold_harmonic_band_powers(s.domain, s.pairs, u, 3);
  double total = 0;
  for (double p : r.power) total += p;
  const double by_hand = (0.49 + 0.16 + 0.09 + 0.25) / (s.domain.total_area * 9.0);
  EXPECT_NEAR(total, by_hand, 1e-12);
  EXPECT_NEAR(total, squared_cv(u, s.domain.vertex_mass), 1e-10);
  // Dimensionless: scaling the field changes nothing.
  IntrinsicVertexData<double> scaled = u;
  for (double& x : scaled) x *= 250.0;
  const ManifoldHarmonicBands q = manifold_harmonic_band_powers(s.domain, s.pairs, scaled, 3);
  for (int b = 0; b < 3; ++b) EXPECT_NEAR(q.power[b], r.power[b], 1e-12 * std::max(1.0, r.power[b]));
  // Coefficients: c_k = phi_k^T M u, c_0 = 3 * sqrt(A) (phi_0 = 1/sqrt(A)), c_1 = 0.7.
  const Eigen::VectorXd c = manifold_harmonic_coefficients(s.pairs, s.domain.vertex_mass, u);
  EXPECT_NEAR(std::abs(c[0]), 3.0 * std::sqrt(s.domain.total_area), 1e-9);
  EXPECT_NEAR(c[1], 0.7, 1e-9);
  EXPECT_NEAR(c[2], 0.0, 1e-9);

  EXPECT_THROW(manifold_harmonic_band_powers(s.domain, s.pairs, IntrinsicVertexData<double>(5, 1.0), 3), InputError);
  EXPECT_THROW(manifold_harmonic_band_powers(s.domain, s.pairs, u, 0), InputError);
  EXPECT_THROW(manifold_harmonic_band_powers(s.domain, s.pairs, IntrinsicVertexData<double>(s.domain.vertex_count, 0.0), 3),
               InputError);
}

struct SquareFixture {
  InputMesh input = load_mesh("shape:square");  // 1 m x 1 m, z = 0, 32 x 32 cells
  SurfaceDomain domain = build_surface_domain(intrinsic_mesh_from_input(input));
  std::vector<Eigen::Vector2d> xy = planar_vertex_coordinates(domain, input);
};

const SquareFixture& square() {
  static const SquareFixture f;
  return f;
}

template <class F>
IntrinsicVertexData<double> sample_xy(const std::vector<Eigen::Vector2d>& xy, F f) {
  IntrinsicVertexData<double> u(xy.size());
  for (size_t v = 0; v < xy.size(); ++v) u[v] = f(xy[v]);
  return u;
}

TEST(SpectralMetrics, PlanarCoordinatesAreTheInputPlane) {
  const SquareFixture& s = square();
  ASSERT_EQ(s.xy.size(), s.input.positions.size());
  for (size_t v = 0; v < s.xy.size(); ++v) {
    EXPECT_NEAR(s.xy[v].x(), s.input.positions[v].x(), 1e-14);
    EXPECT_NEAR(s.xy[v].y(), s.input.positions[v].y(), 1e-14);
  }
  const InputMesh sphere_mesh = load_mesh("shape:sphere");
  const SurfaceDomain sphere_domain = build_surface_domain(intrinsic_mesh_from_input(sphere_mesh));
  EXPECT_THROW(planar_vertex_coordinates(sphere_domain, sphere_mesh), InputError);
}

TEST(SpectralMetrics, RasterisationInterpolatesLinearFieldsExactly) {
  const SquareFixture& s = square();
  auto linear = [](const Eigen::Vector2d& p) { return 1.0 + 2.0 * p.x() + 3.0 * p.y(); };
  const GridSamples g = rasterize_planar_field(s.xy, s.domain.face_vertices, sample_xy(s.xy, linear), 40);
  ASSERT_EQ(g.size, 40);
  EXPECT_NEAR(g.cell, 1.0 / 40, 1e-15);
  EXPECT_NEAR(g.origin.x(), 0.0, 1e-14);
  EXPECT_NEAR(g.origin.y(), 0.0, 1e-14);
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) {
      ASSERT_TRUE(g.covered[j * 40 + i]) << i << ", " << j;
      EXPECT_NEAR(g.value[j * 40 + i], linear(Eigen::Vector2d((i + 0.5) / 40, (j + 0.5) / 40)), 1e-12);
    }
  // On the unit disk only the cells inside the circle are covered: about pi/4 of them.
  const InputMesh disk = load_mesh("shape:disk");
  std::vector<Eigen::Vector2d> dxy;
  for (const auto& p : disk.positions) dxy.emplace_back(p.x(), p.y());
  const GridSamples d = rasterize_planar_field(dxy, disk.triangles, IntrinsicVertexData<double>(dxy.size(), 1.0), 64);
  int covered = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const Eigen::Vector2d centre = d.origin + d.cell * Eigen::Vector2d(i + 0.5, j + 0.5);
      covered += d.covered[j * 64 + i];
      if (centre.norm() < 0.99) {
        EXPECT_TRUE(d.covered[j * 64 + i]);
      }
      if (centre.norm() > 1.0) {
        EXPECT_FALSE(d.covered[j * 64 + i]);
      }
      if (d.covered[j * 64 + i]) {
        EXPECT_NEAR(d.value[j * 64 + i], 1.0, 1e-12);
      }
    }
  EXPECT_NEAR(covered / 4096.0, kPi / 4, 0.01);
}

TEST(SpectralMetrics, GridIsASquareCentredOnTheBoundingBox) {
  // The unit square stretched to 2 x 1: the grid is 2 x 2 centred on it, so its origin is (0, -0.5),
  // and the rows below y = 0 and above y = 1 (half of them) are off the mesh.
  const SquareFixture& s = square();
  std::vector<Eigen::Vector2d> xy = s.xy;
  for (Eigen::Vector2d& p : xy) p.x() *= 2.0;
  auto linear = [](const Eigen::Vector2d& p) { return 1.0 - p.x() + 4.0 * p.y(); };
  const GridSamples g = rasterize_planar_field(xy, s.domain.face_vertices, sample_xy(xy, linear), 32);
  EXPECT_NEAR(g.cell, 2.0 / 32, 1e-15);
  EXPECT_NEAR(g.origin.x(), 0.0, 1e-14);
  EXPECT_NEAR(g.origin.y(), -0.5, 1e-14);
  int covered = 0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      const Eigen::Vector2d centre(2.0 * (i + 0.5) / 32, -0.5 + 2.0 * (j + 0.5) / 32);
      const bool inside = centre.y() > 0.0 && centre.y() < 1.0;
      EXPECT_EQ(static_cast<bool>(g.covered[j * 32 + i]), inside) << i << ", " << j;
      if (inside) {
        EXPECT_NEAR(g.value[j * 32 + i], linear(centre), 1e-12);
      }
      covered += g.covered[j * 32 + i];
    }
  EXPECT_EQ(covered, 32 * 16);
}

TEST(SpectralMetrics, OnTheDiskTheMeanAndParsevalUseTheCoveredCellsOnly) {
  // u = 2 + x on the unit disk: the covered cells are symmetric about x = 0, so their mean is 2
  // (over all cells of the grid it would be 2 pi/4). Uncovered cells count as the mean, so the
  // spectrum's total is sum over covered cells of (g - 2)^2 / (cells * 4).
  const InputMesh disk = load_mesh("shape:disk");
  std::vector<Eigen::Vector2d> xy;
  for (const auto& p : disk.positions) xy.emplace_back(p.x(), p.y());
  IntrinsicVertexData<double> u(xy.size());
  for (size_t v = 0; v < xy.size(); ++v) u[v] = 2.0 + xy[v].x();
  const GridSamples g = rasterize_planar_field(xy, disk.triangles, u, 32);
  const RadialSpectrum r = radial_power_spectrum(g);
  EXPECT_NEAR(r.mean, 2.0, 1e-12);
  EXPECT_NEAR(r.side, 2.0, 1e-12);
  double squares = 0;
  for (int c = 0; c < 32 * 32; ++c)
    if (g.covered[c]) squares += (g.value[c] - 2.0) * (g.value[c] - 2.0);
  double total = 0;
  for (size_t q = 0; q < r.power.size(); ++q) total += r.power[q] * r.count[q];
  EXPECT_NEAR(total, squares / (32 * 32 * 4.0), 1e-12);
  // The linear ramp is a long wave: its power is concentrated at the lowest radii.
  EXPECT_GT(r.power[1] * r.count[1], 0.5 * total);
}

TEST(SpectralMetrics, PlaneWavePeaksAtItsWavenumber) {
  const SquareFixture& s = square();
  for (int k : {2, 3, 5}) {
    // u = 2 + cos(2 pi k x): all variance (1/2, over mean^2 = 4: 1/8) at (kx, ky) = (+-k, 0).
    const IntrinsicVertexData<double> u =
        sample_xy(s.xy, [k](const Eigen::Vector2d& p) { return 2.0 + std::cos(2 * kPi * k * p.x()); });
    const RadialSpectrum r = radial_power_spectrum(s.xy, s.domain.face_vertices, u, 64);
    EXPECT_NEAR(r.side, 1.0, 1e-14);
    EXPECT_NEAR(r.mean, 2.0, 1e-3);
    int peak = 1;
    for (size_t q = 1; q < r.power.size(); ++q)
      if (r.power[q] > r.power[peak]) peak = static_cast<int>(q);
    EXPECT_EQ(peak, k);
    // Linear interpolation on 32 cells damps the wave slightly (by ~sinc^4(pi k / 32) in power).
    // Linear interpolation between the mesh's nodes (spacing 1/32) damps the wave's amplitude by
    // sinc^2(k/32), so its power by sinc^4(k/32) = 0.975, 0.944, 0.850 for k = 2, 3, 5; the cell-centre
    // samples alias a further ~2% away at k = 5.
    const double sinc = std::sin(kPi * k / 32) / (kPi * k / 32);
    const double expected = 0.125 * std::pow(sinc, 4);
    EXPECT_NEAR(r.power[k] * r.count[k], expected, 0.03 * expected) << k;
    // Most of the variance is in that annulus.
    double total = 0;
    for (size_t q = 0; q < r.power.size(); ++q) total += r.power[q] * r.count[q];
    EXPECT_GT(r.power[k] * r.count[k], 0.97 * total) << k;
    EXPECT_LT(r.power[0], 1e-25);  // the mean is subtracted
  }
  // An oblique wave cos(2 pi (3 x + 4 y)) has |k| = 5.
  const IntrinsicVertexData<double> u =
      sample_xy(s.xy, [](const Eigen::Vector2d& p) { return 2.0 + std::cos(2 * kPi * (3 * p.x() + 4 * p.y())); });
  const RadialSpectrum r = radial_power_spectrum(s.xy, s.domain.face_vertices, u, 64);
  int peak = 1;
  for (size_t q = 1; q < r.power.size(); ++q)
    if (r.power[q] > r.power[peak]) peak = static_cast<int>(q);
  EXPECT_EQ(peak, 5);
}

TEST(SpectralMetrics, RadialSpectrumSatisfiesParsevalAndCountsEveryFrequencyOnce) {
  const SquareFixture& s = square();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.5, 1.5);
  IntrinsicVertexData<double> u(s.xy.size());
  for (double& x : u) x = uniform(rng);
  const int n = 48;
  const GridSamples g = rasterize_planar_field(s.xy, s.domain.face_vertices, u, n);
  const RadialSpectrum r = radial_power_spectrum(g);
  // Every one of the n^2 frequencies in exactly one annulus; radii 0 .. round(sqrt(2) n / 2) = 34.
  int frequencies = 0;
  for (int c : r.count) frequencies += c;
  EXPECT_EQ(frequencies, n * n);
  EXPECT_EQ(r.count.size(), 35u);
  EXPECT_EQ(r.count[0], 1);
  EXPECT_EQ(r.count[1], 8);  // (+-1, 0), (0, +-1), (+-1, +-1): |k| = 1 and 1.414 both round to 1
  // Parseval: sum over annuli of mean power x count = grid variance / grid mean^2.
  double mean = 0, variance = 0;
  for (double x : g.value) mean += x;
  mean /= n * n;
  for (double x : g.value) variance += (x - mean) * (x - mean);
  variance /= n * n;
  double total = 0;
  for (size_t q = 0; q < r.power.size(); ++q) total += r.power[q] * r.count[q];
  EXPECT_NEAR(r.mean, mean, 1e-14);
  EXPECT_NEAR(total, variance / (mean * mean), 1e-12);
  // Scale free.
  IntrinsicVertexData<double> scaled = u;
  for (double& x : scaled) x *= 1e3;
  const RadialSpectrum q = radial_power_spectrum(s.xy, s.domain.face_vertices, scaled, n);
  for (size_t k = 0; k < r.power.size(); ++k) EXPECT_NEAR(q.power[k], r.power[k], 1e-12 * r.power[k] + 1e-30);
  EXPECT_THROW(radial_power_spectrum(s.xy, s.domain.face_vertices, IntrinsicVertexData<double>(s.xy.size(), 0.0), n),
               InputError);
}

TEST(SpectralMetrics, AgentDensityDispersionKnownPlacements) {
  // Faces of area 1, 3, 2, 2 (total 8).
  const IntrinsicFaceData<double> area{1.0, 3.0, 2.0, 2.0};
  // Exactly proportional to area: 1, 3, 2, 2 agents -> no dispersion.
  AgentDensityDispersion d = agent_density_dispersion({0, 1, 1, 1, 2, 2, 3, 3}, area);
  EXPECT_NEAR(d.dispersion, 0.0, 1e-15);
  EXPECT_NEAR(d.uniform_expectation, 3.0 / 8.0, 1e-15);
  // All on face 0 (p = 1/8): (1 - p) / p = 7.
  d = agent_density_dispersion({0, 0, 0, 0, 0}, area);
  EXPECT_NEAR(d.dispersion, 7.0, 1e-13);
  // All on face 1 (p = 3/8): 5/3.
  EXPECT_NEAR(agent_density_dispersion({1, 1}, area).dispersion, 5.0 / 3.0, 1e-13);
  // Two agents on faces 2 and 3 (p = 1/4 each): relative densities 0, 0, 2, 2 ->
  // 1/8 + 3/8 + 1/4 + 1/4 = 1.
  EXPECT_NEAR(agent_density_dispersion({2, 3}, area).dispersion, 1.0, 1e-13);
  EXPECT_THROW(agent_density_dispersion({}, area), InputError);
  EXPECT_THROW(agent_density_dispersion({4}, area), InputError);
  EXPECT_THROW(agent_density_dispersion({0}, IntrinsicFaceData<double>{1.0, 0.0}), InputError);
}

TEST(SpectralMetrics, AgentDensityDispersionOfUniformPlacementIsTheShotNoiseFloor) {
  // Agents placed independently with probability proportional to area: E[D] = (F - 1) / N.
  const IntrinsicFaceData<double> area{0.5, 1.0, 2.0, 0.25, 1.25, 3.0, 0.75, 1.5, 1.0, 0.5};
  std::mt19937_64 rng(99);
  std::discrete_distribution<int> pick(area.begin(), area.end());
  const int agents = 200, runs = 4000;
  double sum = 0;
  std::vector<int> faces(agents);
  for (int run = 0; run < runs; ++run) {
    for (int& f : faces) f = pick(rng);
    sum += agent_density_dispersion(faces, area).dispersion;
  }
  // chi^2 with 9 dof has sd sqrt(18); over 4000 runs the mean of D has sd ~ sqrt(18/4000)/200.
  EXPECT_NEAR(sum / runs, 9.0 / agents, 4 * std::sqrt(18.0 / runs) / agents);
}

}  // namespace
}  // namespace physarum
