#pragma once
// The statistical decision of the long-horizon differential harness (independent seeds per
// backend, and planted faults it must reject): two backends are run with independent seeds, each seed gives ONE number
// per metric (a time average after burn-in), and for each metric we test whether the two arm means
// agree within a declared margin.
//
// Why TOST and not a plain t test: a t test that fails to reject "the means differ" is no evidence
// that they agree (few seeds always "pass"). Two one-sided tests (Schuirmann 1987) turn the
// question around: the null hypothesis is |mu_a - mu_b| >= margin, and equivalence is claimed only
// when both one-sided nulls (difference <= -margin, difference >= +margin) are rejected at level
// alpha. With too few seeds TOST fails, as a harness must.
//
// Why Welch: the two backends need not have the same seed-to-seed spread (a planted fault often
// changes the spread too), so the variances are not pooled; the degrees of freedom come from the
// Welch-Satterthwaite formula and are in general not an integer.
//
// Why Sidak: several metrics are tested at once and equivalence is claimed only when all of them
// pass. Running each of m tests at alpha' = 1 - (1 - alpha)^(1/m) keeps the family-wise chance of a
// false "equivalent" at most alpha when the tests are independent (and close to it otherwise).
//
// The unit of replication is the seed. Never pass the vertex values of one field as a sample: they
// are strongly correlated, and a test on them would claim absurd precision.
//
// The Student t and normal distributions come from Boost.Math (header-only, Debian's
// libboost-math-dev) with its default policy; Boost's errors are reported as InputError. The
// tests check them against closed forms (1, 2 and 4 degrees of freedom) and printed tables.
#include <string>
#include <vector>

namespace physarum {

// A number with all its digits, as the statistics' error messages print it.
std::string exact_number(double v);

// ---- distributions -------------------------------------------------------------------------------

// P(T <= t) for Student's t with `df` > 0 degrees of freedom (df need not be an integer; +infinity
// gives the standard normal). The lower tail is accurate to a few ulps; for t > 0 the result is
// 1 - (upper tail), so ask for small upper tails as student_t_cdf(-t, df). Throws InputError for
// df <= 0 or a NaN t.
double student_t_cdf(double t, double df);

// The t with P(T <= t) = p, for 0 < p < 1 (Boost's quantile, to about machine precision). Throws InputError
// for p outside (0, 1) or df <= 0.
double student_t_quantile(double p, double df);

// Standard normal CDF and quantile (the df = infinity limit; used for the normal-approximation start
// and the alpha-spending function). The quantile needs 0 < p < 1.
double standard_normal_cdf(double z);
double standard_normal_quantile(double p);

// ---- samples -------------------------------------------------------------------------------------

// One arm of the comparison for one metric: the per-seed values summarised.
struct SampleSummary {
  int n = 0;
  double mean = 0.0;
  double sd = 0.0;  // sample standard deviation (divisor n - 1)
};

// Mean and sample standard deviation of per-seed values. Throws InputError for fewer than 2 values
// or a non-finite value.
SampleSummary summarize_samples(const std::vector<double>& per_seed_values);

// ---- the test ------------------------------------------------------------------------------------

// Everything a report needs to show for one metric.
struct TostResult {
  SampleSummary a, b;
  double difference = 0.0;          // a.mean - b.mean
  double standard_error = 0.0;      // sqrt(sa^2/na + sb^2/nb)
  double degrees_of_freedom = 0.0;  // Welch-Satterthwaite
  double margin = 0.0;              // equivalence is |mu_a - mu_b| < margin
  double alpha = 0.0;               // per-test level the decision used (already Sidak-adjusted)
  double t_lower = 0.0;             // (difference + margin) / standard_error
  double t_upper = 0.0;             // (difference - margin) / standard_error
  double p_lower = 0.0;             // H0: mu_a - mu_b <= -margin, p = P(T >= t_lower)
  double p_upper = 0.0;             // H0: mu_a - mu_b >= +margin, p = P(T <= t_upper)
  double p = 0.0;                   // max(p_lower, p_upper), the TOST p-value
  bool equivalent = false;          // p < alpha
};

// Welch two-sample TOST. margin > 0, 0 < alpha < 1, each arm at least 2 seeds. When both standard
// deviations are zero the standard error is zero: the arms are then equivalent exactly when
// |difference| < margin (p = 0), else not (p = 1).
TostResult welch_tost(const SampleSummary& a, const SampleSummary& b, double margin, double alpha);
TostResult welch_tost(const std::vector<double>& a, const std::vector<double>& b, double margin, double alpha);

// Per-test level 1 - (1 - family_alpha)^(1/tests) for `tests` >= 1 simultaneous tests.
double sidak_alpha(double family_alpha, int tests);

// ---- how many seeds ------------------------------------------------------------------------------
//
// The power calculation, stated: both arms get n seeds and share the per-seed standard deviation
// sd (estimated from a pilot run). Then the difference of means has standard error
// se(n) = sd * sqrt(2 / n) and Welch's degrees of freedom are df = 2 (n - 1). TOST rejects both
// nulls when  -margin + t_{1-alpha,df} se < difference < margin - t_{1-alpha,df} se.
// Approximating (difference - true_difference) / se by a central t with df degrees of freedom (the
// "shifted t" approximation of Chow, Shao & Wang, Sample Size Calculations in Clinical Research,
// sec. 3.2), the probability of that is
//   power(n) = T_df((margin - delta)/se - t_{1-alpha,df}) + T_df((margin + delta)/se - t_{1-alpha,df}) - 1
// with delta = |true_difference|, clipped at 0. For delta = 0 and large df this is the familiar
//   n >= 2 sd^2 (z_{1-alpha} + z_{1-beta/2})^2 / margin^2,   beta = 1 - power.
// tost_seeds_per_arm returns the smallest n >= 2 with power(n) >= the target, found by galloping
// from the normal-approximation n (steps 1, 2, 4, ... up or down) to a bracket and bisecting it
// (power(n) increases with n).

// The approximate power above for n seeds per arm (n >= 2).
double tost_power(double sd, double margin, double alpha, int n, double true_difference = 0.0);

// Smallest n per arm reaching `power` (0 < power < 1). alpha is the per-test level (pass the Sidak
// value when several metrics are tested). Requires sd >= 0, margin > |true_difference|. Throws
// InputError when more than 1,000,000 seeds would be needed.
int tost_seeds_per_arm(double sd, double margin, double alpha, double power, double true_difference = 0.0);

}  // namespace physarum
