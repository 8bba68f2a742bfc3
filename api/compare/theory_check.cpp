#include "api/compare/theory_check.hpp"

#include "common/harness/equivalence_test.hpp"

#include <cmath>
#include <cstdio>

namespace physarum {
namespace {

constexpr const char* kMeanMetric = "mean_over_U";

int metric_index(const Arm& arm, const std::string& name) {
  for (size_t j = 0; j < arm.metrics.size(); ++j)
    if (arm.metrics[j].name == name) return static_cast<int>(j);
  return -1;
}

TheoryRow judge(const Arm& arm, const std::vector<double>& per_seed, double margin, double alpha) {
  TheoryRow row;
  row.label = arm.label;
  row.expected = *arm.expected_mean_over_U;
  const SampleSummary measured = summarize_samples(per_seed);
  // A one-sample test: the expected value has no spread (Welch's degrees of freedom become n - 1).
  const TostResult t = welch_tost(measured, SampleSummary{measured.n, row.expected, 0.0}, margin, alpha);
  row.seeds = measured.n;
  row.mean = measured.mean;
  row.sd = measured.sd;
  row.difference = t.difference;
  row.margin = margin;
  row.p_value = t.p;
  const double half = t.standard_error > 0.0 ? student_t_quantile(1.0 - alpha, t.degrees_of_freedom) * t.standard_error : 0.0;
  row.ci_low = t.difference - half;
  row.ci_high = t.difference + half;
  row.verdict = t.equivalent ? "equivalent"
                : (row.ci_low >= margin || row.ci_high <= -margin) ? "different"
                                                                   : "inconclusive";
  return row;
}

}  // namespace

std::vector<TheoryRow> check_against_theory(const std::vector<const Arm*>& arms,
                                            const std::vector<const std::vector<std::vector<double>>*>& values,
                                            double family_alpha) {
  std::vector<size_t> judged;
  for (size_t i = 0; i < arms.size(); ++i)
    if (arms[i]->expected_mean_over_U && metric_index(*arms[i], kMeanMetric) >= 0 && values[i]->size() >= 2)
      judged.push_back(i);
  std::vector<TheoryRow> rows;
  if (judged.empty()) return rows;
  const double alpha = sidak_alpha(family_alpha, static_cast<int>(judged.size()));
  for (size_t i : judged) {
    const Arm& arm = *arms[i];
    const int j = metric_index(arm, kMeanMetric);
    std::vector<double> per_seed;
    for (const std::vector<double>& seed : *values[i]) per_seed.push_back(seed[static_cast<size_t>(j)]);
    rows.push_back(judge(arm, per_seed, arm.metrics[static_cast<size_t>(j)].margin, alpha));
  }
  return rows;
}

nlohmann::ordered_json theory_json(const std::vector<TheoryRow>& rows) {
  if (rows.empty()) return nullptr;
  nlohmann::ordered_json arms = nlohmann::ordered_json::array();
  for (const TheoryRow& r : rows)
    arms.push_back({{"label", r.label},
                    {"verdict", r.verdict},
                    {"expected_mean_over_U", r.expected},
                    {"mean_over_U", r.mean},
                    {"sd", r.sd},
                    {"seeds", r.seeds},
                    {"difference", r.difference},
                    {"confidence_interval", {r.ci_low, r.ci_high}},
                    {"margin", r.margin},
                    {"p_value", r.p_value}});
  nlohmann::ordered_json j;
  j["what"] = "each arm's mean / U against the steady mean of the time-discrete model it simulates (Eq. 5's U "
              "times the discretisation's factor); reported only: the comparison's verdict and exit code come "
              "from the arms against each other";
  j["arms"] = arms;
  return j;
}

std::string theory_line(const TheoryRow& r) {
  char text[320];
  std::snprintf(text, sizeof text,
                "physarum compare: theory: %s mean/U %.4f +- %.4f (%d seeds) against the time-discrete model's "
                "%.4f: %s (difference %+.4f, interval [%+.4f, %+.4f], margin %.3g)",
                r.label.c_str(), r.mean, r.sd, r.seeds, r.expected, r.verdict.c_str(), r.difference, r.ci_low,
                r.ci_high, r.margin);
  return text;
}

}  // namespace physarum
