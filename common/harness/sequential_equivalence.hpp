#pragma once
// A three-way, group-sequential version of the harness's decision (common/harness/equivalence_test.hpp):
// seeds are run in batches, and after each batch ("look") every metric is judged Equivalent,
// Different or still undecided, so that a clear comparison stops early and a hard one gets up to a
// declared maximum of seeds per arm before it is called Inconclusive.
//
// One metric at one look, with per-metric level a, d = mean_a - mean_b, the Welch standard error se
// and Welch degrees of freedom df:
//   Equivalent  d - t se > -margin and d + t se < margin, t = t_{1-a,df}: TOST at level a (the
//               1 - 2a confidence interval lies inside (-margin, margin)). A false Equivalent
//               (true |delta| >= margin) has probability <= a.
//   Different   d - t' se > margin or d + t' se < -margin, t' = t_{1-a/2,df}: the 1 - a two-sided
//               interval lies entirely outside the margin, so |delta| > margin with confidence 1 - a.
//               (With t_{1-a} instead, a true difference of 0 and a margin small against se could
//               trip either side and the error would approach 2a; the half level on each side keeps
//               it <= a for every |delta| <= margin.)
//   undecided   otherwise.
// When both arms are constant (se = 0) the decision is exact: Equivalent when |d| < margin,
// Different when |d| > margin, undecided at |d| = margin.
//
// Looks and the alpha-spending function. The comparison declares N_max seeds per arm. At a look
// with n seeds per arm (the smaller arm when they differ) the information fraction is
// t = min(n / N_max, 1). The cumulative level spent by information t is the O'Brien-Fleming-type
// function of Lan & DeMets (1983):
//   alpha*(t) = 2 - 2 Phi(z_{1-alpha/2} / sqrt t),   alpha*(0) = 0, alpha*(1) = alpha,
// and look k tests at the increment alpha*(t_k) - alpha*(t_{k-1}). The look that reaches N_max is
// the last and spends whatever remains. Each kind of false verdict has probability at most the sum
// of the per-look levels (the union bound over looks) = alpha, whatever the correlation between the
// looks (they share seeds). That is conservative: exact group-sequential boundaries (recursive
// numerical integration over the joint distribution of the look statistics, Armitage-McPherson-Rowe)
// would spend alpha exactly. We chose the union bound because it is simple and provably valid with
// Welch's t and unequal, data-driven batch sizes (the exact recursion assumes known variances and a
// fixed correlation structure). What it gives away is bounded by what the looks before the last
// spend, alpha*(t_{K-1}), since the last look alone already errs with its own level: with
// O'Brien-Fleming spending early looks cost almost nothing (alpha*(0.5) = 0.0056 of 0.05, so looks at
// half and full waste at most that), but a look shortly before N_max spends a lot (alpha*(0.9) =
// 0.039 of 0.05), leaving the last look a small level. Look often early, rarely late.
//
// Several metrics (m): a look's increment is split with Sidak, each metric tested at
// 1 - (1 - increment)^(1/m), m fixed for the whole comparison (letting m shrink as metrics get
// decided would make the levels depend on the data and break the simple bound above). A metric
// decided at some look keeps that verdict and the numbers it was decided with; undecided metrics
// are tested again at later looks. So easy metrics drop out while hard ones gather seeds.
//
// Overall verdict after a look: Different as soon as any metric is Different; Equivalent once every
// metric is Equivalent (every metric not marked difference-only); otherwise Continue before N_max and
// Inconclusive at the last look.
//
// For every metric a look also reports what the seeds would buy at the final look's level (the
// level the look reaching N_max has, or would have if it came next): the achieved power
// tost_power(pooled sd, margin, final level, n) of declaring equivalence when the arms are truly
// equal, and, for an undecided metric, the seeds per arm that would settle it,
// tost_seeds_per_arm(pooled sd, margin, final level, power 0.9).
#include "common/harness/equivalence_test.hpp"

#include <vector>

namespace physarum {

enum class Verdict { Equivalent, Different, Inconclusive, Continue };

// "equivalent", "different", "inconclusive", "continue".
const char* to_string(Verdict verdict);

// alpha*(t) above: the cumulative level spent by information fraction t. 0 for t <= 0, exactly
// alpha for t >= 1; 0 < alpha < 1 (InputError otherwise, or for a NaN t).
double obrien_fleming_spent(double alpha, double information_fraction);

// One metric's state after a look.
struct MetricLook {
  // Equivalent or Different once decided (then frozen); Continue while undecided with looks left
  // (and so after a comparison that ended Different early); Inconclusive when undecided at the
  // last look.
  Verdict verdict = Verdict::Continue;
  int decided_at_look = 0;      // 1-based look of the decision; 0 while undecided
  double difference = 0.0;      // a.mean - b.mean
  double standard_error = 0.0;  // Welch
  double df = 0.0;              // Welch-Satterthwaite (+infinity when se = 0)
  double margin = 0.0;
  double level = 0.0;           // this metric's level at this look (Sidak share of the increment)
  double ci_low = 0.0, ci_high = 0.0;        // d -/+ t_{1-level} se: Equivalent iff inside (-margin, margin)
  double outer_low = 0.0, outer_high = 0.0;  // d -/+ t_{1-level/2} se: Different iff outside [-margin, margin]
  double p_equivalent = 1.0;    // TOST p-value (H0: |delta| >= margin); Equivalent iff < level
  double p_different = 1.0;     // p-value of H0: |delta| <= margin; Different iff < level
  double achieved_power = 0.0;  // tost_power(pooled sd, margin, final level, current n per arm)
  int seeds_to_settle = 0;      // seeds per arm for power 0.9 at the final level; 0 when decided,
                                // -1 when more than 1,000,000 would be needed
  SampleSummary a, b;
};

class SequentialEquivalence {
 public:
  // metrics >= 1, 0 < family_alpha < 1, max_seeds_per_arm >= 2; InputError otherwise.
  SequentialEquivalence(int metrics, double family_alpha, int max_seeds_per_arm);

  // One look: the per-metric summaries of both arms over all seeds so far (not just the new batch)
  // and the metrics' margins (absolute, > 0). Every look must have more seeds per arm than the
  // previous one (the smaller arm counts), every arm at least 2. Returns the overall verdict;
  // calling again after Equivalent, Different or Inconclusive is an InputError.
  Verdict look(const std::vector<SampleSummary>& a, const std::vector<SampleSummary>& b,
               const std::vector<double>& margins);

  // Metrics that can make the comparison Different but are not needed for Equivalent (a scale only
  // one of two triangulations resolves, common/harness/comparison_metrics.hpp): the overall verdict
  // is Equivalent once every OTHER metric is. Default: none. InputError on a wrong size.
  void set_difference_only(const std::vector<bool>& mask);

  const std::vector<MetricLook>& metrics() const { return metrics_; }
  int looks() const { return looks_; }
  int seeds_per_arm() const { return seeds_; }       // n of the latest look (the smaller arm)
  double alpha_spent() const { return spent_; }      // alpha*(t) of the latest look
  double family_alpha() const { return alpha_; }
  int max_seeds_per_arm() const { return max_seeds_; }
  Verdict verdict() const { return verdict_; }       // Continue before the first look

 private:
  int metric_count_;
  double alpha_;
  int max_seeds_;
  int looks_ = 0;
  int seeds_ = 0;
  double spent_ = 0.0;
  Verdict verdict_ = Verdict::Continue;
  std::vector<MetricLook> metrics_;
  std::vector<bool> difference_only_;
};

}  // namespace physarum
