#pragma once
// The check of each arm against theory, apart from the arms' comparison with each other: where an
// arm's continuous model has Eq. 5's steady mean U (steady_mean_is_U), its measured mean / U must
// lie within the mean's margin of the value the time-discrete model reaches
// (common/model/discrete_steady_state.hpp: 1 with one forward-Euler sub-step or backward Euler,
// above 1 with several sub-steps or a fractional activation step). It answers "does each backend
// simulate the model?", not "do the two arms agree?": `physarum compare` reports it in its own
// section of verdict.json and on stderr, and it never decides the comparison's verdict or exit code.
#include "api/compare/comparison_arms.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace physarum {

struct TheoryRow {
  std::string label;          // the arm's
  double expected = 1.0;      // the time-discrete model's steady mean / U
  int seeds = 0;
  double mean = 0.0, sd = 0.0;  // of the per-seed mean / U
  double difference = 0.0;    // mean - expected
  double ci_low = 0.0, ci_high = 0.0;  // of the difference, at level 1 - 2 alpha
  double margin = 0.0;        // absolute, the scene's compare_margin_mean
  double p_value = 1.0;       // one-sample TOST against `expected`
  std::string verdict;        // "equivalent" (interval inside +-margin), "different" (outside), "inconclusive"
};

// One row per arm that has an expected value and a mean_over_U metric; `values[i]` are arm i's
// per-seed metrics (columns in arms[i].metrics order). Sidak over the rows at `family_alpha`.
std::vector<TheoryRow> check_against_theory(const std::vector<const Arm*>& arms,
                                            const std::vector<const std::vector<std::vector<double>>*>& values,
                                            double family_alpha);

// The "theory" section of verdict.json (null when there is no row) and the line per row on stderr.
nlohmann::ordered_json theory_json(const std::vector<TheoryRow>& rows);
std::string theory_line(const TheoryRow& row);

}  // namespace physarum
