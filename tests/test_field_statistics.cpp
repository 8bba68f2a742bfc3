// Statistics of a per-vertex field (paper Sec. 3.2): lumped-mass mean, the analytic U of Eq. 5,
// coverage fractions, and the stats.csv line format the README documents.
#include "common/setup/agent_inputs.hpp"
#include "common/simulation/field_statistics.hpp"

#include "common/base/errors.hpp"
#include "pheromone_test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace physarum {
namespace {

using V = IntrinsicVertexData<double>;
constexpr double kNoTurnover = std::numeric_limits<double>::infinity();  // mean_lifetime null

TEST(FieldStatistics, MeanIsWeightedByLumpedMass) {
  // (1*2 + 3*6) / (1 + 3) = 5; an unweighted mean would give 4.
  EXPECT_DOUBLE_EQ(area_weighted_mean(V{2.0, 6.0}, V{1.0, 3.0}), 5.0);
  EXPECT_THROW(area_weighted_mean(V{1.0}, V{1.0, 2.0}), InputError);
  EXPECT_THROW(area_weighted_mean(V{1.0}, V{0.0}), InputError);
}

// On the unit sphere the mass-weighted mean of z^2 approximates its surface average 1/3, and of z
// (odd) vanishes: checks that the weights are the per-vertex areas, not a uniform 1/n.
TEST(FieldStatistics, MeanOnSphereMatchesSurfaceIntegral) {
  const InputMesh sphere = testing::make_icosphere(3);
  const SurfaceDomain domain = testing::make_domain(sphere);
  V z(sphere.positions.size()), z2(sphere.positions.size());
  for (size_t i = 0; i < z.size(); ++i) z[i] = sphere.positions[i].z(), z2[i] = z[i] * z[i];
  EXPECT_NEAR(area_weighted_mean(z2, domain.vertex_mass), 1.0 / 3.0, 2e-3);
  EXPECT_NEAR(area_weighted_mean(z, domain.vertex_mass), 0.0, 1e-12);
}

TEST(FieldStatistics, UniformSteadyStateFollowsEquationFive) {
  // N r_dep / (r_dec A) = 100 * 2 / (0.5 * 4) = 100; times exp(-t_a / tau) = exp(-0.2).
  EXPECT_DOUBLE_EQ(uniform_steady_state(100, 2.0, 0.5, 4.0, 0.2, 1.0), 100.0 * std::exp(-0.2));
  EXPECT_DOUBLE_EQ(uniform_steady_state(100, 2.0, 0.5, 4.0, 0.2, kNoTurnover), 100.0);
  EXPECT_DOUBLE_EQ(uniform_steady_state(100, 2.0, 0.5, 4.0, 0.0, 0.3), 100.0);
  // The paper's Fig. 5 keeps U fixed by raising N as tau falls: N exp(-t_a/tau) constant.
  EXPECT_NEAR(uniform_steady_state(1000, 1.0, 1.0, 1.0, 0.2, 1.0),
              uniform_steady_state(static_cast<int>(std::lround(1000 * std::exp(0.2 / 0.5 - 0.2))), 1.0, 1.0, 1.0,
                                   0.2, 0.5),
              1.0);
  Scene s;
  s.agent_model().agents = 50;
  s.agent_model().parameters[Param::deposit_rate] = 3.0;
  s.agent_model().parameters[Param::decay_rate] = 1.5;
  s.agent_model().parameters[Param::activation_time] = 0.1;
  s.agent_model().parameters[Param::mean_lifetime] = 0.4;
  EXPECT_DOUBLE_EQ(uniform_steady_state(s, 2.0), 50 * 3.0 / (1.5 * 2.0) * std::exp(-0.25));
  EXPECT_THROW(uniform_steady_state(1, 1.0, 0.0, 1.0, 0.0, kNoTurnover), InputError);
}

TEST(FieldStatistics, CoverageIsMassFractionStrictlyAboveThreshold) {
  const V mass{1.0, 2.0, 3.0, 4.0};
  const V u{0.0, 1.0, 2.0, 4.0};
  EXPECT_DOUBLE_EQ(coverage_fraction(u, mass, 0.5), 0.9);  // masses 2 + 3 + 4 of 10
  EXPECT_DOUBLE_EQ(coverage_fraction(u, mass, 2.0), 0.4);  // 2.0 is not strictly above
  EXPECT_DOUBLE_EQ(coverage_fraction(u, mass, 10.0), 0.0);
  const FieldStatistics s = compute_field_statistics(u, mass, 2.0);
  EXPECT_DOUBLE_EQ(s.mean, (0 + 2 + 6 + 16) / 10.0);
  EXPECT_DOUBLE_EQ(s.U, 2.0);
  EXPECT_DOUBLE_EQ(s.coverage[0], 0.7);  // 0.5 U = 1: values 2 and 4, masses 3 + 4
  EXPECT_DOUBLE_EQ(s.coverage[1], 0.4);  // 1 U = 2: value 4 only
  EXPECT_DOUBLE_EQ(s.coverage[2], 0.0);  // 2 U = 4: nothing strictly above
}

TEST(FieldStatistics, CsvHeaderAndRowMatchDesign) {
  EXPECT_EQ(stats_csv_header(), "time,mean,U,coverage_0.5U,coverage_1U,coverage_2U");
  FieldStatistics s;
  s.mean = 0.125;
  s.U = 0.25;
  s.coverage = {0.5, 0.375, 0.0};
  std::stringstream row(stats_csv_row(1.5, s));
  std::vector<double> cells;
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(std::stod(cell));
  EXPECT_EQ(cells, (std::vector<double>{1.5, 0.125, 0.25, 0.5, 0.375, 0.0}));
}

}  // namespace
}  // namespace physarum
