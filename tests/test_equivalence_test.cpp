// The statistics of the differential harness against answers obtained without this code: closed
// forms of the t distribution (computed through Boost.Math) for 1, 2 and 4 degrees of freedom, printed
// t tables, numerical quadrature of the t density (Simpson's rule on the substituted tail integral,
// 200,000 panels, done separately in Python), TOST examples worked out by hand, and a Monte Carlo
// check of the power formula.
#include "common/harness/equivalence_test.hpp"
#include "common/base/errors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace physarum {
namespace {

TEST(EquivalenceTest, TDistributionMatchesClosedFormsForSmallDegreesOfFreedom) {
  for (double t : {-30.0, -4.0, -1.0, -0.2, 0.0, 0.3, 1.0, 2.5, 12.0}) {
    // df = 1 is the Cauchy distribution.
    EXPECT_NEAR(student_t_cdf(t, 1.0), 0.5 + std::atan(t) / std::numbers::pi, 1e-13) << t;
    // df = 2: F(t) = 1/2 + t / (2 sqrt(2 + t^2)).
    EXPECT_NEAR(student_t_cdf(t, 2.0), 0.5 + t / (2.0 * std::sqrt(2.0 + t * t)), 1e-13) << t;
    // df = 4: F(t) = 1/2 + (3/8) (t / sqrt(1 + t^2/4)) (1 - t^2 / (12 (1 + t^2/4))).
    const double s = 1.0 + t * t / 4.0;
    EXPECT_NEAR(student_t_cdf(t, 4.0), 0.5 + 0.375 * t / std::sqrt(s) * (1.0 - t * t / (12.0 * s)), 1e-13) << t;
  }
  // The quantile is the inverse, closed forms again: tan(pi (p - 1/2)) and (2p-1)/sqrt(2p(1-p)).
  // (Cauchy written as -cot(pi p): tan(pi (p - 1/2)) loses digits near its pole at small p.)
  for (double p : {1e-9, 0.01, 0.3, 0.5, 0.77, 0.975, 0.999999}) {
    const double cauchy = p == 0.5 ? 0.0 : -1.0 / std::tan(std::numbers::pi * p);
    EXPECT_NEAR(student_t_quantile(p, 1.0), cauchy, 1e-9 * std::max(1.0, std::abs(cauchy))) << p;
    const double two = (2 * p - 1) / std::sqrt(2 * p * (1 - p));
    EXPECT_NEAR(student_t_quantile(p, 2.0), two, 1e-9 * std::max(1.0, std::abs(two))) << p;
  }
}

TEST(EquivalenceTest, TDistributionMatchesTablesAndQuadrature) {
  // Upper tail P(T > 2) with 10 df = 0.036694 (tables); quadrature 0.0366940173854.
  EXPECT_NEAR(1.0 - student_t_cdf(2.0, 10.0), 0.0366940173854, 1e-10);
  EXPECT_NEAR(student_t_cdf(-2.0, 10.0), 0.0366940173854, 1e-10);
  // Further quadrature values, including non-integer degrees of freedom as Welch produces.
  EXPECT_NEAR(student_t_cdf(-2.5, 8.0), 0.0184710188568, 1e-10);
  EXPECT_NEAR(student_t_cdf(-3.5, 8.0), 0.00403954113021, 1e-11);
  EXPECT_NEAR(student_t_cdf(-1.3, 2.5), 0.150243394635, 1e-10);
  EXPECT_NEAR(student_t_cdf(-0.4, 7.3), 0.350301871043, 1e-10);
  EXPECT_NEAR(student_t_cdf(-4.2, 3.0), 0.0123160390885, 1e-10);
  // Printed critical values (6 decimals).
  EXPECT_NEAR(student_t_quantile(0.975, 10.0), 2.228139, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.95, 1.0), 6.313752, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.995, 5.0), 4.032143, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.975, 30.0), 2.042272, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.99, 20.0), 2.527977, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.025, 10.0), -2.228139, 1e-6);
  // Round trip at a Welch-like df.
  for (double p : {0.001, 0.2, 0.6, 0.95}) EXPECT_NEAR(student_t_cdf(student_t_quantile(p, 8.384), 8.384), p, 1e-12);
  // Huge df tends to the normal: z_0.975 = 1.959964, z_0.95 = 1.644854 (Python statistics.NormalDist).
  // At 1e9 df the t quantile still lies (z^3 + z) / (4 df) = 2.4e-9 above z (the first term of its
  // Cornish-Fisher expansion in 1/df; the next is O(1/df^2)): 1.9599639869123253.
  EXPECT_NEAR(student_t_quantile(0.975, 1e9), 1.9599639869123253, 1e-12);
  EXPECT_NEAR(student_t_quantile(0.975, 1e5), 1.9599639845, 1e-4);
  EXPECT_NEAR(standard_normal_quantile(0.95), 1.6448536270, 1e-9);
  EXPECT_NEAR(standard_normal_quantile(1e-10), -6.3613409024, 1e-8);
  // df = +infinity is the normal distribution exactly.
  EXPECT_DOUBLE_EQ(student_t_cdf(-1.5, std::numeric_limits<double>::infinity()), standard_normal_cdf(-1.5));
  EXPECT_NEAR(student_t_quantile(0.975, std::numeric_limits<double>::infinity()), 1.9599639845, 1e-9);
  // Bad arguments are InputError, whether caught before Boost or reported by it (a NaN t).
  EXPECT_THROW(student_t_quantile(1.0, 5.0), InputError);
  EXPECT_THROW(student_t_quantile(0.5, -1.0), InputError);
  EXPECT_THROW(student_t_cdf(1.0, 0.0), InputError);
  EXPECT_THROW(student_t_cdf(NAN, 4.0), InputError);
  EXPECT_THROW(standard_normal_cdf(NAN), InputError);
  EXPECT_THROW(standard_normal_quantile(0.0), InputError);
}

TEST(EquivalenceTest, SidakPerTestAlpha) {
  // 1 - 0.95^(1/5) = 0.0102062183130.
  EXPECT_NEAR(sidak_alpha(0.05, 5), 0.0102062183130, 1e-12);
  EXPECT_DOUBLE_EQ(sidak_alpha(0.05, 1), 0.05);
  // m tests at the Sidak level have family-wise level alpha exactly (independent tests).
  const double a = sidak_alpha(0.1, 7);
  EXPECT_NEAR(1.0 - std::pow(1.0 - a, 7), 0.1, 1e-14);
  EXPECT_THROW(sidak_alpha(0.05, 0), InputError);
}

TEST(EquivalenceTest, SummaryUsesTheSampleStandardDeviation) {
  const SampleSummary s = summarize_samples({1.0, 2.0, 3.0, 4.0, 5.0});
  EXPECT_EQ(s.n, 5);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_NEAR(s.sd, std::sqrt(2.5), 1e-15);  // divisor n - 1: 10 / 4
  EXPECT_THROW(summarize_samples({1.0}), InputError);
  EXPECT_THROW(summarize_samples({1.0, NAN}), InputError);
}

TEST(EquivalenceTest, WelchTostWithTwoDegreesOfFreedomWorkedByHand) {
  // a = {0, 2}: mean 1, variance 2. b = {2.5, 4.5}: mean 3.5, variance 2. Difference -2.5,
  // SE = sqrt(2/2 + 2/2) = sqrt 2, Welch df = (1 + 1)^2 / (1/1 + 1/1) = 2. Margin 4:
  //   t_lower = (-2.5 + 4)/sqrt 2 = 1.06066, t^2 = 1.125, p_lower = 1/2 - t/(2 sqrt(2 + t^2)) = 1/2 - 0.3 = 0.2
  //   t_upper = (-2.5 - 4)/sqrt 2 = -4.59619, p_upper = 1/2 - 4.59619/(2 sqrt(23.125)) = 0.0221105
  const TostResult r = welch_tost(std::vector<double>{0.0, 2.0}, std::vector<double>{2.5, 4.5}, 4.0, 0.05);
  EXPECT_DOUBLE_EQ(r.a.mean, 1.0);
  EXPECT_DOUBLE_EQ(r.b.mean, 3.5);
  EXPECT_NEAR(r.a.sd, std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(r.b.sd, std::sqrt(2.0), 1e-15);
  EXPECT_EQ(r.a.n, 2);
  EXPECT_DOUBLE_EQ(r.difference, -2.5);
  EXPECT_NEAR(r.standard_error, std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(r.degrees_of_freedom, 2.0, 1e-14);
  EXPECT_NEAR(r.t_lower, 1.5 / std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(r.t_upper, -6.5 / std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(r.p_lower, 0.2, 1e-13);
  const double t = 6.5 / std::sqrt(2.0);
  EXPECT_NEAR(r.p_upper, 0.5 - t / (2.0 * std::sqrt(2.0 + t * t)), 1e-13);
  EXPECT_NEAR(r.p_upper, 0.0221105, 1e-7);
  EXPECT_NEAR(r.p, 0.2, 1e-13);
  EXPECT_FALSE(r.equivalent);
  // The same data with the arms swapped: the roles of the two one-sided tests swap.
  const TostResult s = welch_tost(std::vector<double>{2.5, 4.5}, std::vector<double>{0.0, 2.0}, 4.0, 0.05);
  EXPECT_NEAR(s.p_upper, 0.2, 1e-13);
  EXPECT_NEAR(s.p_lower, r.p_upper, 1e-13);
}

TEST(EquivalenceTest, WelchTostWithUnequalSpreadsAndSizes) {
  // a (5 seeds): mean 10.0, sd sqrt(0.3/4) = 0.273861. b (7 seeds): mean 10.528571, sd 0.256348.
  // va = 0.015, vb = 0.0657143/7 = 0.00938776, SE = 0.156166,
  // df = (va + vb)^2 / (va^2/4 + vb^2/6) = 8.384221 (by hand / Python statistics).
  const std::vector<double> a = {10.1, 9.8, 10.4, 10.0, 9.7};
  const std::vector<double> b = {10.6, 10.2, 10.9, 10.3, 10.8, 10.5, 10.4};
  TostResult r = welch_tost(a, b, 1.0, 0.05);
  EXPECT_NEAR(r.difference, -0.5285714285714, 1e-12);
  EXPECT_NEAR(r.a.sd, 0.2738612787526, 1e-12);
  EXPECT_NEAR(r.b.sd, 0.2563479777847, 1e-12);
  EXPECT_NEAR(r.standard_error, 0.1561657936363, 1e-12);
  EXPECT_NEAR(r.degrees_of_freedom, 8.384221148554, 1e-10);
  EXPECT_NEAR(r.t_lower, 3.018769734726, 1e-10);
  EXPECT_NEAR(r.t_upper, -9.788132170172, 1e-10);
  // p-values by quadrature of the t density at df = 8.384221.
  EXPECT_NEAR(r.p_lower, 0.00785930985186, 1e-10);
  EXPECT_NEAR(r.p_upper, 3.573994289515e-06, 1e-12);
  EXPECT_DOUBLE_EQ(r.p, r.p_lower);
  EXPECT_TRUE(r.equivalent);
  // Still equivalent at the Sidak level for 5 metrics (0.0102 > 0.00786) ...
  EXPECT_TRUE(welch_tost(a, b, 1.0, sidak_alpha(0.05, 5)).equivalent);
  // ... but not at 10 metrics (0.00512), nor with the tighter margin 0.8 (p = 0.0593338).
  EXPECT_FALSE(welch_tost(a, b, 1.0, sidak_alpha(0.05, 10)).equivalent);
  r = welch_tost(a, b, 0.8, 0.05);
  EXPECT_NEAR(r.p, 0.0593338193393, 1e-9);
  EXPECT_FALSE(r.equivalent);
}

TEST(EquivalenceTest, WelchTostEdgeCases) {
  // Constant arms: exact decision.
  EXPECT_TRUE(welch_tost(std::vector<double>{1, 1, 1}, std::vector<double>{1.5, 1.5}, 1.0, 0.05).equivalent);
  EXPECT_FALSE(welch_tost(std::vector<double>{1, 1, 1}, std::vector<double>{2.5, 2.5}, 1.0, 0.05).equivalent);
  // One constant arm: df = n - 1 of the other arm.
  EXPECT_NEAR(welch_tost(std::vector<double>{1, 1, 1}, std::vector<double>{0, 1, 2, 3}, 9.0, 0.05).degrees_of_freedom,
              3.0, 1e-14);
  EXPECT_THROW(welch_tost(std::vector<double>{1, 2}, std::vector<double>{1, 2}, 0.0, 0.05), InputError);
  EXPECT_THROW(welch_tost(std::vector<double>{1, 2}, std::vector<double>{1, 2}, 1.0, 1.5), InputError);
  EXPECT_THROW(welch_tost(std::vector<double>{1}, std::vector<double>{1, 2}, 1.0, 0.05), InputError);
}

TEST(EquivalenceTest, SeedsPerArmFromThePowerCalculation) {
  // sd = margin = 1, alpha = 0.05, power 0.8, true difference 0. Normal approximation:
  // 2 (z_0.95 + z_0.9)^2 = 2 (1.644854 + 1.281552)^2 = 17.13 -> 18. The t version (Python, by
  // quadrature) gives power 0.76921 at n = 17 and 0.80071 at n = 18.
  EXPECT_NEAR(tost_power(1.0, 1.0, 0.05, 17), 0.769212808259, 1e-6);
  EXPECT_NEAR(tost_power(1.0, 1.0, 0.05, 18), 0.800712526750, 1e-6);
  EXPECT_EQ(tost_seeds_per_arm(1.0, 1.0, 0.05, 0.8), 18);
  // Non-zero true difference 0.2, power 0.95: 0.945259 at 34, 0.950480 at 35.
  EXPECT_NEAR(tost_power(1.0, 1.0, 0.05, 34, 0.2), 0.945258770300, 1e-6);
  EXPECT_NEAR(tost_power(1.0, 1.0, 0.05, 35, -0.2), 0.950479729606, 1e-6);
  EXPECT_EQ(tost_seeds_per_arm(1.0, 1.0, 0.05, 0.95, 0.2), 35);
  // Scale invariance: only sd / margin matters.
  EXPECT_EQ(tost_seeds_per_arm(0.03, 0.03, 0.05, 0.8), 18);
  // Halving the margin roughly quadruples n; a perfectly reproducible metric needs the minimum.
  const int quarter = tost_seeds_per_arm(1.0, 0.5, 0.05, 0.8);
  EXPECT_GE(quarter, 4 * 17);
  EXPECT_LE(quarter, 4 * 18 + 1);
  EXPECT_EQ(tost_seeds_per_arm(0.0, 1.0, 0.05, 0.8), 2);
  EXPECT_THROW(tost_seeds_per_arm(1.0, 0.2, 0.05, 0.8, 0.3), InputError);
  EXPECT_THROW(tost_seeds_per_arm(1.0, 1e-4, 0.05, 0.8), InputError);  // ~1.7e9 seeds
}

TEST(EquivalenceTest, PowerFormulaAgreesWithSimulatedTostRuns) {
  // Run the actual Welch TOST on normal samples of equal means and count how often it declares
  // equivalence: that fraction estimates the true power (Monte Carlo SE ~0.004 for 10,000 runs).
  // The shifted-t formula must be within 0.02 of it, and the power it targets must be reached.
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double sd = 1.0, margin = 1.0, alpha = 0.05;
  const int n = tost_seeds_per_arm(sd, margin, alpha, 0.8);
  int accepted = 0;
  const int runs = 10000;
  std::vector<double> a(n), b(n);
  for (int run = 0; run < runs; ++run) {
    for (int i = 0; i < n; ++i) {
      a[i] = normal(rng) * sd;
      b[i] = normal(rng) * sd;
    }
    if (welch_tost(a, b, margin, alpha).equivalent) ++accepted;
  }
  const double simulated = static_cast<double>(accepted) / runs;
  EXPECT_NEAR(simulated, tost_power(sd, margin, alpha, n), 0.02);
  EXPECT_GT(simulated, 0.78);
}

}  // namespace
}  // namespace physarum
