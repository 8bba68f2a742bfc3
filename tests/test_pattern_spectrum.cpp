// The spectral-peak helpers of the reaction-diffusion wavelength tests (tests/pattern_spectrum.hpp)
// on fields whose spectrum is known exactly: a zonal spherical harmonic has all its power in its own
// degree, and a plane wave on the flat square peaks at its number of cycles per side.
#include "pattern_spectrum.hpp"
#include "reaction_diffusion_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace physarum {
namespace {

TEST(PatternSpectrum, ZonalHarmonicHasAllItsPowerInItsDegree) {
  // 1 + 0.1 P_6(z) on the unit sphere: degree 6 only (the 1 is the mean, removed).
  SurfaceSpec spec;
  spec.mesh = "shape:sphere";
  const PreparedSurface surface = prepare_surface(spec);
  const auto p = testing::vertex_positions(surface);
  IntrinsicVertexData<double> field(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    const double z = p[i].z() / p[i].norm(), z2 = z * z;
    field[i] = 1.0 + 0.1 * (231 * z2 * z2 * z2 - 315 * z2 * z2 + 105 * z2 - 5) / 16;
  }
  const auto peak = testing::spherical_peak(p, surface.domain.vertex_mass, field, 1.0, 12);
  EXPECT_EQ(peak.peak.bin, 6);
  double total = 0.0;
  for (const double x : peak.power) total += x;
  EXPECT_GT(peak.power[6] / total, 0.99);
  // |c_60|^2 = (0.1)^2 4 pi / 13 (P_6 = sqrt(4 pi / 13) Y_60), spread over the 13 orders' mean;
  // the lumped-mass quadrature is good to a few percent at 2,562 vertices.
  EXPECT_NEAR(peak.power[6], 0.01 * 4 * std::numbers::pi / 13 / 13, 0.03 * 0.01 * 4 * std::numbers::pi / 13 / 13);
  // Its wavenumber is sqrt(6 x 7): the centroid over degrees 4..8 is that of degree 6 alone.
  EXPECT_NEAR(peak.wavenumber, std::sqrt(42.0), 0.01 * std::sqrt(42.0));
}

TEST(PatternSpectrum, PlaneWaveOnTheSquarePeaksAtItsCyclesPerSide) {
  // cos(2 pi 7 x) + 2 on the unit square: 7 cycles per side, wavenumber 14 pi rad/m.
  SurfaceSpec spec;
  spec.mesh = "shape:square";
  spec.max_circumradius = 0.01;
  const PreparedSurface surface = prepare_surface(spec);
  const auto xy = planar_vertex_coordinates(surface.domain, surface.simulated);
  IntrinsicVertexData<double> field(xy.size());
  for (size_t i = 0; i < xy.size(); ++i) field[i] = 2.0 + std::cos(2.0 * std::numbers::pi * 7.0 * xy[i].x());
  const auto peak = testing::radial_peak(surface, field, 128);
  EXPECT_EQ(peak.peak.bin, 7);
  EXPECT_NEAR(peak.side, 1.0, 1e-9);
  EXPECT_NEAR(peak.wavenumber, 14.0 * std::numbers::pi, 0.02 * 14.0 * std::numbers::pi);
}

}  // namespace
}  // namespace physarum
