#pragma once
// Scalar summaries of a per-vertex field (paper Sec. 3.2): the area-weighted mean with the lumped
// mass, the analytic Uniform Steady-state Pheromone Concentration U (Eq. 5) and coverage, the area
// fraction where the field exceeds a multiple of U. These are the columns of stats.csv.
#include "common/base/element_data.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// sum_i m_i u_i / sum_i m_i. Throws InputError on size mismatch or non-positive total mass.
double area_weighted_mean(const IntrinsicVertexData<double>& values, const IntrinsicVertexData<double>& mass);

// Eq. 5: U = N r_dep / (r_dec A) * exp(-t_a / tau); no turnover (tau = +infinity) gives factor 1,
// since then every agent is eventually older than t_a.
double uniform_steady_state(int agents, double deposit_rate, double decay_rate, double area,
                            double activation_time, double mean_lifetime);

// Area fraction (by lumped mass) of the vertices whose value is strictly above `threshold`.
double coverage_fraction(const IntrinsicVertexData<double>& values, const IntrinsicVertexData<double>& mass, double threshold);

// The multiples k of U whose coverage stats.csv reports (columns coverage_0.5U, coverage_1U, coverage_2U).
inline constexpr std::array<double, 3> kCoverageMultiples = {0.5, 1.0, 2.0};

struct FieldStatistics {
  double mean = 0.0;
  double U = 0.0;
  std::array<double, 3> coverage{};  // for kCoverageMultiples, in order
};

FieldStatistics compute_field_statistics(const IntrinsicVertexData<double>& values, const IntrinsicVertexData<double>& mass, double U);

// stats.csv: "time,mean,U,coverage_0.5U,coverage_1U,coverage_2U" (no trailing newline).
std::string stats_csv_header();
// One row matching the header, full precision (no trailing newline).
std::string stats_csv_row(double time, const FieldStatistics& stats);

}  // namespace physarum
