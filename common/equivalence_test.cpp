#include "common/equivalence_test.hpp"

#include "common/errors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

namespace physarum {
namespace {

// Above this many degrees of freedom the t distribution is replaced by the normal: the difference
// is below 1e-7 there, and lgamma's cancellation in the beta prefactor would cost more than that.
constexpr double kNormalDegreesOfFreedom = 1e7;

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Continued fraction for I_x(a, b) (the standard one, converging quickly for x < (a+1)/(a+b+2)):
//   I_x(a,b) = x^a (1-x)^b / (a B(a,b)) * 1/(1 + d1/(1 + d2/(1 + ...)))
//   d_{2m+1} = -(a+m)(a+b+m) x / ((a+2m)(a+2m+1)),   d_{2m} = m (b-m) x / ((a+2m-1)(a+2m)),
// evaluated front to back with the modified Lentz method. y = 1 - x is passed separately so that
// callers who know it exactly (the t distribution near t = 0) do not lose it to cancellation.
double incomplete_beta_fraction(double a, double b, double x, double y) {
  constexpr double tiny = 1e-300;
  constexpr double eps = 1e-15;
  // Lentz for b0 + a1/(b1 + a2/(b2 + ...)) with b0 = 0, a1 = 1, a_{j+1} = d_j, b_j = 1.
  double f = tiny, c = f, d = 0.0;
  bool converged = false;
  for (int j = 1; j <= 10000; ++j) {
    double aj;
    if (j == 1) {
      aj = 1.0;
    } else {
      const int k = j - 1;  // d_k
      if (k % 2 == 1) {
        const double m = (k - 1) / 2;
        aj = -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1));
      } else {
        const double m = k / 2;
        aj = m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
      }
    }
    d = 1.0 + aj * d;
    if (std::abs(d) < tiny) d = tiny;
    d = 1.0 / d;
    c = 1.0 + aj / c;
    if (std::abs(c) < tiny) c = tiny;
    const double delta = c * d;
    f *= delta;
    if (std::abs(delta - 1.0) < eps) {
      converged = true;
      break;
    }
  }
  if (!converged)
    throw InputError("incomplete beta: continued fraction did not converge for a = " + num(a) + ", b = " + num(b) +
                     ", x = " + num(x));
  const double log_prefix = a * std::log(x) + b * std::log(y) - (std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b));
  return std::exp(log_prefix) * f / a;
}

// I_x(a, b) with both x and y = 1 - x given; picks the side where the fraction converges fast.
double incomplete_beta(double a, double b, double x, double y) {
  if (x <= 0.0) return 0.0;
  if (y <= 0.0) return 1.0;
  if (x < (a + 1.0) / (a + b + 2.0)) return incomplete_beta_fraction(a, b, x, y);
  return 1.0 - incomplete_beta_fraction(b, a, y, x);
}

// P(T <= t) for t <= 0 (the lower tail, computed without cancellation).
double t_lower_tail(double t, double df) {
  if (df > kNormalDegreesOfFreedom) return standard_normal_cdf(t);
  const double t2 = t * t;
  // P(|T| > |t|) = I_{df/(df+t^2)}(df/2, 1/2); the lower tail is half of it.
  return 0.5 * incomplete_beta(0.5 * df, 0.5, df / (df + t2), t2 / (df + t2));
}

double t_density(double t, double df) {
  if (df > kNormalDegreesOfFreedom) return std::exp(-0.5 * t * t) / std::sqrt(2.0 * std::numbers::pi);
  const double log_norm =
      std::lgamma(0.5 * (df + 1.0)) - std::lgamma(0.5 * df) - 0.5 * std::log(df * std::numbers::pi);
  return std::exp(log_norm - 0.5 * (df + 1.0) * std::log1p(t * t / df));
}

// The x <= 0 with lower_tail(x) = q for 0 < q <= 0.5: bracket, then Newton steps kept inside the
// bracket (bisection whenever Newton would leave it).
template <class Tail, class Density>
double lower_tail_quantile(double q, Tail lower_tail, Density density) {
  if (q == 0.5) return 0.0;
  double lo = -1.0, hi = 0.0;
  while (lower_tail(lo) > q) {
    hi = lo;
    lo *= 2.0;
    if (!std::isfinite(lo)) return -std::numeric_limits<double>::infinity();
  }
  double x = 0.5 * (lo + hi);
  for (int iter = 0; iter < 500; ++iter) {
    const double fx = lower_tail(x) - q;
    if (fx == 0.0) return x;
    if (fx > 0.0) hi = x; else lo = x;
    const double dens = density(x);
    double next = dens > 0.0 ? x - fx / dens : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::abs(next - x);
    x = next;
    if (step <= 1e-14 * std::max(1.0, std::abs(x)) || hi - lo <= 1e-15 * std::max(1.0, std::abs(x))) return x;
  }
  return x;
}

void check_probability(double p, const char* what) {
  if (!(p > 0.0 && p < 1.0)) throw InputError(std::string(what) + ": probability " + num(p) + " is not in (0, 1)");
}

void check_df(double df, const char* what) {
  if (!(df > 0.0)) throw InputError(std::string(what) + ": degrees of freedom " + num(df) + " are not > 0");
}

}  // namespace

double regularized_incomplete_beta(double a, double b, double x) {
  if (!(a > 0.0) || !(b > 0.0) || !(x >= 0.0 && x <= 1.0))
    throw InputError("incomplete beta: needs a > 0, b > 0 and 0 <= x <= 1 (a = " + num(a) + ", b = " + num(b) +
                     ", x = " + num(x) + ")");
  return incomplete_beta(a, b, x, 1.0 - x);
}

double standard_normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

double standard_normal_quantile(double p) {
  check_probability(p, "normal quantile");
  const double q = std::min(p, 1.0 - p);
  const double x = lower_tail_quantile(
      q, [](double z) { return standard_normal_cdf(z); },
      [](double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); });
  return p > 0.5 ? -x : x;
}

double student_t_cdf(double t, double df) {
  check_df(df, "t distribution");
  if (std::isnan(t)) return t;
  return t <= 0.0 ? t_lower_tail(t, df) : 1.0 - t_lower_tail(-t, df);
}

double student_t_quantile(double p, double df) {
  check_probability(p, "t quantile");
  check_df(df, "t quantile");
  // Solve in the lower tail, where the tail probability is represented without cancellation.
  const double q = std::min(p, 1.0 - p);
  const double x = lower_tail_quantile(
      q, [df](double t) { return t_lower_tail(t, df); }, [df](double t) { return t_density(t, df); });
  return p > 0.5 ? -x : x;
}

SampleSummary summarize_samples(const std::vector<double>& values) {
  if (values.size() < 2)
    throw InputError("equivalence test: need at least 2 seeds per arm, got " + std::to_string(values.size()));
  SampleSummary s;
  s.n = static_cast<int>(values.size());
  double sum = 0.0;
  for (double v : values) {
    if (!std::isfinite(v)) throw InputError("equivalence test: a per-seed value is not finite (" + num(v) + ")");
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
    throw InputError("equivalence test: margin " + num(margin) + " is not a positive number");
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
  const double critical = student_t_quantile(1.0 - alpha, df);
  const double power = student_t_cdf((margin - delta) / se - critical, df) +
                       student_t_cdf((margin + delta) / se - critical, df) - 1.0;
  return std::max(0.0, power);
}

int tost_seeds_per_arm(double sd, double margin, double alpha, double power, double true_difference) {
  check_probability(power, "TOST sample size power");
  check_probability(alpha, "TOST sample size alpha");
  if (!(sd >= 0.0) || !std::isfinite(sd)) throw InputError("TOST sample size: sd " + num(sd) + " is not >= 0");
  const double delta = std::abs(true_difference);
  if (!(margin > delta))
    throw InputError("TOST sample size: margin " + num(margin) + " must exceed the assumed true difference " +
                     num(delta));
  constexpr int kMaxSeeds = 1000000;
  // Normal-approximation start: 2 sd^2 (z_{1-alpha} + z_{1-beta/2})^2 / (margin - delta)^2.
  const double beta = 1.0 - power;
  const double z = standard_normal_quantile(1.0 - alpha) + standard_normal_quantile(1.0 - 0.5 * beta);
  const double start = 2.0 * sd * sd * z * z / ((margin - delta) * (margin - delta));
  int hi = static_cast<int>(std::clamp(std::ceil(start), 2.0, static_cast<double>(kMaxSeeds)));
  // Grow until enough (the t quantiles usually ask for a few seeds more than the normal start).
  while (tost_power(sd, margin, alpha, hi, true_difference) < power) {
    if (hi >= kMaxSeeds)
      throw InputError("TOST sample size: more than " + std::to_string(kMaxSeeds) +
                       " seeds per arm would be needed (sd " + num(sd) + ", margin " + num(margin) + ")");
    hi = std::min(kMaxSeeds, 2 * hi);
  }
  // Smallest n in [2, hi] with enough power (power grows with n).
  int lo = 1;  // invariant: power(lo) < target or lo == 1; power(hi) >= target
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    if (tost_power(sd, margin, alpha, mid, true_difference) >= power) hi = mid; else lo = mid;
  }
  return hi;
}

}  // namespace physarum
