#include "common/harness/equivalence_test.hpp"

#include "common/base/errors.hpp"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace physarum {

std::string exact_number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

namespace {

void check_probability(double p, const char* what) {
  if (!(p > 0.0 && p < 1.0)) throw InputError(std::string(what) + ": probability " + exact_number(p) + " is not in (0, 1)");
}

void check_df(double df, const char* what) {
  if (!(df > 0.0)) throw InputError(std::string(what) + ": degrees of freedom " + exact_number(df) + " are not > 0");
}

// Runs one Boost.Math evaluation and reports its errors (domain, overflow, evaluation: under
// Boost's default policy they are thrown, all derived from std::exception) as InputError naming the
// function and its arguments. The message is built only on failure: these run in inner loops.
template <class F>
double boost_math(const char* what, double x, double df, F&& evaluate) {
  try {
    return evaluate();
  } catch (const std::exception& e) {
    std::string message = std::string(what) + " at " + exact_number(x);
    if (!std::isnan(df)) message += " with " + exact_number(df) + " degrees of freedom";
    throw InputError(message + ": " + e.what());
  }
}

// Boost's default promotes double arguments to long double internally, which costs a factor of
// about five in speed (the sequential harness's Monte Carlo tests call these millions of times);
// without it the results are still accurate to a few ulps (the tests check 1e-13 against closed forms).
using Policy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
using Normal = boost::math::normal_distribution<double, Policy>;
using StudentT = boost::math::students_t_distribution<double, Policy>;

constexpr double kNoDf = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double standard_normal_cdf(double z) {
  return boost_math("normal CDF", z, kNoDf, [z] { return boost::math::cdf(Normal(), z); });
}

double standard_normal_quantile(double p) {
  check_probability(p, "normal quantile");
  return boost_math("normal quantile", p, kNoDf,
                    [p] { return boost::math::quantile(Normal(), p); });
}

double student_t_cdf(double t, double df) {
  check_df(df, "t distribution");
  if (std::isinf(df)) return standard_normal_cdf(t);
  return boost_math("t distribution CDF", t, df,
                    [t, df] { return boost::math::cdf(StudentT(df), t); });
}

double student_t_quantile(double p, double df) {
  check_probability(p, "t quantile");
  check_df(df, "t quantile");
  if (std::isinf(df)) return standard_normal_quantile(p);
  return boost_math("t quantile", p, df,
                    [p, df] { return boost::math::quantile(StudentT(df), p); });
}

SampleSummary summarize_samples(const std::vector<double>& values) {
  if (values.size() < 2)
    throw InputError("equivalence test: need at least 2 seeds per arm, got " + std::to_string(values.size()));
  SampleSummary s;
  s.n = static_cast<int>(values.size());
  double sum = 0.0;
  for (double v : values) {
    if (!std::isfinite(v)) throw InputError("equivalence test: a per-seed value is not finite (" + exact_number(v) + ")");
    sum += v;
  }
  s.mean = sum / s.n;
  double squares = 0.0;  // two-pass: no cancellation from subtracting large sums
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(squares / (s.n - 1));
  return s;
}

TostResult welch_tost(const SampleSummary& a, const SampleSummary& b, double margin, double alpha) {
  if (a.n < 2 || b.n < 2)
    throw InputError("equivalence test: need at least 2 seeds per arm, got " + std::to_string(a.n) + " and " +
                     std::to_string(b.n));
  if (!(a.sd >= 0.0) || !(b.sd >= 0.0) || !std::isfinite(a.mean) || !std::isfinite(b.mean))
    throw InputError("equivalence test: arm summaries must have finite means and standard deviations >= 0");
  if (!(margin > 0.0) || !std::isfinite(margin))
    throw InputError("equivalence test: margin " + exact_number(margin) + " is not a positive number");
  check_probability(alpha, "equivalence test alpha");

  TostResult r;
  r.a = a;
  r.b = b;
  r.margin = margin;
  r.alpha = alpha;
  r.difference = a.mean - b.mean;
  const double va = a.sd * a.sd / a.n, vb = b.sd * b.sd / b.n;
  r.standard_error = std::sqrt(va + vb);
  if (r.standard_error == 0.0) {
    // Both arms constant: no sampling error at all, the decision is exact.
    r.degrees_of_freedom = std::numeric_limits<double>::infinity();
    const bool inside = std::abs(r.difference) < margin;
    const double inf = std::numeric_limits<double>::infinity();
    r.t_lower = r.difference + margin > 0.0 ? inf : -inf;
    r.t_upper = r.difference - margin < 0.0 ? -inf : inf;
    r.p_lower = r.difference + margin > 0.0 ? 0.0 : 1.0;
    r.p_upper = r.difference - margin < 0.0 ? 0.0 : 1.0;
    r.p = inside ? 0.0 : 1.0;
    r.equivalent = inside;
    return r;
  }
  // Welch-Satterthwaite: (va + vb)^2 / (va^2/(na-1) + vb^2/(nb-1)).
  r.degrees_of_freedom = (va + vb) * (va + vb) / (va * va / (a.n - 1) + vb * vb / (b.n - 1));
  r.t_lower = (r.difference + margin) / r.standard_error;
  r.t_upper = (r.difference - margin) / r.standard_error;
  r.p_lower = student_t_cdf(-r.t_lower, r.degrees_of_freedom);  // P(T >= t_lower)
  r.p_upper = student_t_cdf(r.t_upper, r.degrees_of_freedom);   // P(T <= t_upper)
  r.p = std::max(r.p_lower, r.p_upper);
  r.equivalent = r.p < alpha;
  return r;
}

TostResult welch_tost(const std::vector<double>& a, const std::vector<double>& b, double margin, double alpha) {
  return welch_tost(summarize_samples(a), summarize_samples(b), margin, alpha);
}

double sidak_alpha(double family_alpha, int tests) {
  check_probability(family_alpha, "Sidak correction");
  if (tests < 1) throw InputError("Sidak correction: number of tests " + std::to_string(tests) + " is not >= 1");
  // 1 - (1 - alpha)^(1/m), written with expm1/log1p to keep digits for small alpha.
  return -std::expm1(std::log1p(-family_alpha) / tests);
}

double tost_power(double sd, double margin, double alpha, int n, double true_difference) {
  if (n < 2) throw InputError("TOST power: need n >= 2 seeds per arm, got " + std::to_string(n));
  if (!(sd >= 0.0) || !(margin > 0.0)) throw InputError("TOST power: needs sd >= 0 and margin > 0");
  check_probability(alpha, "TOST power alpha");
  const double delta = std::abs(true_difference);
  const double se = sd * std::sqrt(2.0 / n);
  if (se == 0.0) return delta < margin ? 1.0 : 0.0;
  const double df = 2.0 * (n - 1);
  const double critical = -student_t_quantile(alpha, df);  // t_{1-alpha}, from the lower tail
  const double power = student_t_cdf((margin - delta) / se - critical, df) +
                       student_t_cdf((margin + delta) / se - critical, df) - 1.0;
  return std::max(0.0, power);
}

int tost_seeds_per_arm(double sd, double margin, double alpha, double power, double true_difference) {
  check_probability(power, "TOST sample size power");
  check_probability(alpha, "TOST sample size alpha");
  if (!(sd >= 0.0) || !std::isfinite(sd)) throw InputError("TOST sample size: sd " + exact_number(sd) + " is not >= 0");
  const double delta = std::abs(true_difference);
  if (!(margin > delta))
    throw InputError("TOST sample size: margin " + exact_number(margin) + " must exceed the assumed true difference " +
                     exact_number(delta));
  constexpr int kMaxSeeds = 1000000;
  const auto enough = [&](int n) { return tost_power(sd, margin, alpha, n, true_difference) >= power; };
  // Normal-approximation start: 2 sd^2 (z_{1-alpha} + z_{1-beta/2})^2 / (margin - delta)^2. The t
  // version usually needs a few seeds more, so gallop from the start (steps 1, 2, 4, ...) to
  // bracket the answer, then bisect: a handful of power evaluations even for thousands of seeds.
  const double beta = 1.0 - power;
  const double z = standard_normal_quantile(1.0 - alpha) + standard_normal_quantile(1.0 - 0.5 * beta);
  const double start_value = 2.0 * sd * sd * z * z / ((margin - delta) * (margin - delta));
  const int start = static_cast<int>(std::clamp(std::ceil(start_value), 2.0, static_cast<double>(kMaxSeeds)));
  int lo = 1, hi = start;  // invariant: lo == 1 or power(lo) < target; power(hi) >= target
  if (enough(start)) {
    for (int step = 1; hi > 2; step *= 2) {
      const int probe = std::max(2, hi - step);
      if (!enough(probe)) {
        lo = probe;
        break;
      }
      hi = probe;
    }
  } else {
    lo = start;
    for (int step = 1;; step *= 2) {
      if (lo >= kMaxSeeds)
        throw InputError("TOST sample size: more than " + std::to_string(kMaxSeeds) +
                         " seeds per arm would be needed (sd " + exact_number(sd) + ", margin " + exact_number(margin) + ")");
      const int probe = static_cast<int>(std::min<long>(kMaxSeeds, static_cast<long>(lo) + step));
      if (enough(probe)) {
        hi = probe;
        break;
      }
      lo = probe;
    }
  }
  // Smallest n in (lo, hi] with enough power (power grows with n).
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    if (enough(mid)) hi = mid; else lo = mid;
  }
  return hi;
}

}  // namespace physarum
