#include "common/harness/sequential_equivalence.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace physarum {
namespace {

void check_alpha(double alpha, const char* what) {
  if (!(alpha > 0.0 && alpha < 1.0))
    throw InputError(std::string(what) + ": alpha " + exact_number(alpha) + " is not in (0, 1)");
}

// Pooled standard deviation of the two arms (divisor na + nb - 2): the common spread the power
// calculation assumes.
double pooled_sd(const SampleSummary& a, const SampleSummary& b) {
  const double squares = (a.n - 1) * a.sd * a.sd + (b.n - 1) * b.sd * b.sd;
  return std::sqrt(squares / (a.n + b.n - 2));
}

// One metric judged at per-metric level `level` (0 < level < 1).
MetricLook judge(const SampleSummary& a, const SampleSummary& b, double margin, double level) {
  const TostResult tost = welch_tost(a, b, margin, level);
  MetricLook m;
  m.a = a;
  m.b = b;
  m.margin = margin;
  m.level = level;
  m.difference = tost.difference;
  m.standard_error = tost.standard_error;
  m.df = tost.degrees_of_freedom;
  const double d = m.difference;
  if (m.standard_error == 0.0) {
    // Both arms constant: no sampling error, the intervals are the point d and the decision exact.
    m.ci_low = m.ci_high = m.outer_low = m.outer_high = d;
    m.p_equivalent = std::abs(d) < margin ? 0.0 : 1.0;
    m.p_different = std::abs(d) > margin ? 0.0 : 1.0;
  } else {
    // Quantiles from the lower tail: 1 - level would lose the digits of a tiny early-look level.
    const double t = -student_t_quantile(level, m.df);
    const double t_outer = -student_t_quantile(0.5 * level, m.df);
    m.ci_low = d - t * m.standard_error;
    m.ci_high = d + t * m.standard_error;
    m.outer_low = d - t_outer * m.standard_error;
    m.outer_high = d + t_outer * m.standard_error;
    m.p_equivalent = tost.p;
    // H0: |delta| <= margin, rejected on either side: d well above +margin (t_upper large) or well
    // below -margin (t_lower very negative); each side at half the level, hence the factor 2.
    const double p_above = student_t_cdf(-tost.t_upper, m.df);  // P(T >= (d - margin)/se)
    const double p_below = student_t_cdf(tost.t_lower, m.df);   // P(T <= (d + margin)/se)
    m.p_different = std::min(1.0, 2.0 * std::min(p_above, p_below));
  }
  if (m.p_equivalent < level) m.verdict = Verdict::Equivalent;
  else if (m.p_different < level) m.verdict = Verdict::Different;
  else m.verdict = Verdict::Continue;
  return m;
}

// A metric that no seeds can judge at this look (the look's level is zero: it came so early that
// alpha*(t) underflowed). Reports the numbers without a decision.
MetricLook unjudged(const SampleSummary& a, const SampleSummary& b, double margin) {
  MetricLook m = judge(a, b, margin, 0.5);  // the point estimates; intervals and p-values replaced
  const double inf = std::numeric_limits<double>::infinity();
  m.level = 0.0;
  m.ci_low = m.outer_low = -inf;
  m.ci_high = m.outer_high = inf;
  m.p_equivalent = m.p_different = 1.0;
  m.verdict = Verdict::Continue;
  return m;
}

}  // namespace

const char* to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::Equivalent: return "equivalent";
    case Verdict::Different: return "different";
    case Verdict::Inconclusive: return "inconclusive";
    case Verdict::Continue: return "continue";
  }
  return "unknown";
}

double obrien_fleming_spent(double alpha, double information_fraction) {
  check_alpha(alpha, "O'Brien-Fleming spending");
  if (std::isnan(information_fraction))
    throw InputError("O'Brien-Fleming spending: the information fraction is NaN");
  if (information_fraction <= 0.0) return 0.0;
  if (information_fraction >= 1.0) return alpha;
  // 2 - 2 Phi(x) written as 2 Phi(-x): the upper tail without cancellation.
  const double z = standard_normal_quantile(1.0 - 0.5 * alpha);
  return 2.0 * standard_normal_cdf(-z / std::sqrt(information_fraction));
}

SequentialEquivalence::SequentialEquivalence(int metrics, double family_alpha, int max_seeds_per_arm)
    : metric_count_(metrics), alpha_(family_alpha), max_seeds_(max_seeds_per_arm) {
  if (metrics < 1)
    throw InputError("sequential equivalence: number of metrics " + std::to_string(metrics) + " is not >= 1");
  check_alpha(family_alpha, "sequential equivalence");
  if (max_seeds_per_arm < 2)
    throw InputError("sequential equivalence: the maximum of seeds per arm " + std::to_string(max_seeds_per_arm) +
                     " is not >= 2");
  metrics_.resize(metrics);
  difference_only_.assign(static_cast<size_t>(metrics), false);
}

void SequentialEquivalence::set_difference_only(const std::vector<bool>& mask) {
  if (mask.size() != difference_only_.size())
    throw InputError("sequential equivalence: " + std::to_string(mask.size()) + " difference-only flags for " +
                     std::to_string(difference_only_.size()) + " metrics");
  difference_only_ = mask;
}

Verdict SequentialEquivalence::look(const std::vector<SampleSummary>& a, const std::vector<SampleSummary>& b,
                                    const std::vector<double>& margins) {
  if (verdict_ != Verdict::Continue)
    throw InputError(std::string("sequential equivalence: the comparison has already ended (") +
                     to_string(verdict_) + ")");
  const auto m = static_cast<std::size_t>(metric_count_);
  if (a.size() != m || b.size() != m || margins.size() != m)
    throw InputError("sequential equivalence: expected " + std::to_string(m) + " metrics, got " +
                     std::to_string(a.size()) + " and " + std::to_string(b.size()) + " arm summaries and " +
                     std::to_string(margins.size()) + " margins");
  int n = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < m; ++i) {
    if (!(margins[i] > 0.0) || !std::isfinite(margins[i]))
      throw InputError("sequential equivalence: the margin of metric " + std::to_string(i) + " (" +
                       exact_number(margins[i]) + ") is not a positive number");
    if (a[i].n < 2 || b[i].n < 2)
      throw InputError("sequential equivalence: metric " + std::to_string(i) + " needs at least 2 seeds per arm, got " +
                       std::to_string(a[i].n) + " and " + std::to_string(b[i].n));
    n = std::min({n, a[i].n, b[i].n});
  }
  if (n <= seeds_)
    throw InputError("sequential equivalence: look " + std::to_string(looks_ + 1) + " has " + std::to_string(n) +
                     " seeds per arm, not more than the previous look's " + std::to_string(seeds_));

  // The level of this look and the level the final look has (this one when it reaches N_max, else
  // a look at N_max right after this one).
  const double fraction = std::min(1.0, static_cast<double>(n) / max_seeds_);
  const bool last = fraction >= 1.0;
  const double spent = obrien_fleming_spent(alpha_, fraction);
  const double increment = last ? alpha_ - spent_ : std::max(0.0, spent - spent_);
  const double level = increment > 0.0 ? sidak_alpha(increment, metric_count_) : 0.0;
  const double final_level = last ? level : sidak_alpha(alpha_ - spent, metric_count_);
  ++looks_;
  seeds_ = n;
  spent_ = spent;

  bool any_different = false, all_equivalent = true;
  for (std::size_t i = 0; i < m; ++i) {
    MetricLook& metric = metrics_[i];
    if (metric.decided_at_look == 0) {
      metric = level > 0.0 ? judge(a[i], b[i], margins[i], level) : unjudged(a[i], b[i], margins[i]);
      const double sd = pooled_sd(a[i], b[i]);
      metric.achieved_power = tost_power(sd, margins[i], final_level, n);
      if (metric.verdict == Verdict::Continue) {
        if (last) metric.verdict = Verdict::Inconclusive;
        try {
          metric.seeds_to_settle = tost_seeds_per_arm(sd, margins[i], final_level, 0.9);
        } catch (const InputError&) {
          metric.seeds_to_settle = -1;  // beyond tost_seeds_per_arm's million
        }
      } else {
        metric.decided_at_look = looks_;
      }
    }
    any_different = any_different || metric.verdict == Verdict::Different;
    all_equivalent = all_equivalent && (metric.verdict == Verdict::Equivalent || difference_only_[i]);
  }
  if (any_different) verdict_ = Verdict::Different;
  else if (all_equivalent) verdict_ = Verdict::Equivalent;
  else verdict_ = last ? Verdict::Inconclusive : Verdict::Continue;
  return verdict_;
}

}  // namespace physarum
