#include "common/simulation/field_statistics.hpp"

#include "common/base/errors.hpp"

#include <cmath>
#include <cstdio>

namespace physarum {
namespace {

void check_sizes(const IntrinsicVertexData<double>& values, const IntrinsicVertexData<double>& mass, const char* what) {
  if (values.size() != mass.size())
    throw InputError(std::string(what) + ": " + std::to_string(values.size()) + " values for " +
                     std::to_string(mass.size()) + " vertex masses");
}

double total(const IntrinsicVertexData<double>& mass, const char* what) {
  double sum = 0.0;
  for (double m : mass) sum += m;
  if (!(sum > 0.0)) throw InputError(std::string(what) + ": total vertex mass " + std::to_string(sum) + " is not > 0");
  return sum;
}

}  // namespace

double area_weighted_mean(const IntrinsicVertexData<double>& values, const IntrinsicVertexData<double>& mass) {
  check_sizes(values, mass, "mean");
  double weighted = 0.0;
  for (size_t i = 0; i < values.size(); ++i) weighted += mass[i] * values[i];
  return weighted / total(mass, "mean");
}

double uniform_steady_state(int agents, double deposit_rate, double decay_rate, double area, double activation_time,
                            double mean_lifetime) {
  if (!(decay_rate > 0.0) || !(area > 0.0))
    throw InputError("U (Eq. 5): decay rate " + std::to_string(decay_rate) + " and area " + std::to_string(area) +
                     " must both be > 0");
  // Without turnover no agent is ever reborn, so after t_a all of them deposit: the factor is 1.
  const double depositing_fraction = std::isinf(mean_lifetime) ? 1.0 : std::exp(-activation_time / mean_lifetime);
  return agents * deposit_rate / (decay_rate * area) * depositing_fraction;
}

double coverage_fraction(const IntrinsicVertexData<double>& values, const IntrinsicVertexData<double>& mass, double threshold) {
  check_sizes(values, mass, "coverage");
  double above = 0.0;
  for (size_t i = 0; i < values.size(); ++i)
    if (values[i] > threshold) above += mass[i];
  return above / total(mass, "coverage");
}

FieldStatistics compute_field_statistics(const IntrinsicVertexData<double>& values, const IntrinsicVertexData<double>& mass, double U) {
  FieldStatistics s;
  s.mean = area_weighted_mean(values, mass);
  s.U = U;
  for (size_t k = 0; k < kCoverageMultiples.size(); ++k)
    s.coverage[k] = coverage_fraction(values, mass, kCoverageMultiples[k] * U);
  return s;
}

std::string stats_csv_header() { return "time,mean,U,coverage_0.5U,coverage_1U,coverage_2U"; }

std::string stats_csv_row(double time, const FieldStatistics& stats) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%.9g,%.17g,%.17g,%.17g,%.17g,%.17g", time, stats.mean, stats.U, stats.coverage[0],
                stats.coverage[1], stats.coverage[2]);
  return buf;
}

}  // namespace physarum
