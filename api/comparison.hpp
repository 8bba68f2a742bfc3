#pragma once
// `physarum compare SCENE.json [--arm K=V[,K=V...] --arm K=V[,...]] [--max-seeds N] [--jobs N]
//                              [--device SPEC] [--fault NAME] [--out DIR]
//                              [--reference-stats FILE] [--reference-seeds N] [--store-reference FILE --seeds N]`:
// the differential harness. Runs independent seeds of two arms (by default the OpenCL backend and
// the reference on one scene; with --arm, one scene under two settings or discretisations,
// api/compare/comparison_arms.hpp), time-averages dimensionless pattern metrics per seed after a burn-in
// (common/harness/comparison_metrics.hpp) and decides, metric by metric, whether the arms agree within the
// scene's declared margins.
//
// Seeds run in batches of kBatch per arm, on every core and device at once (api/compare/seed_runner.hpp);
// after each batch a group-sequential test (common/harness/sequential_equivalence.hpp: O'Brien-Fleming alpha
// spending over the looks, Sidak over the metrics) says, for each metric still open, equivalent (its
// confidence interval lies inside the margin), different (it lies entirely outside) or undecided.
// The run stops as soon as one metric is different or all are equivalent, and at --max-seeds it
// says inconclusive, naming the metrics that lack power and the seeds per arm that would settle
// them. Exit 0 equivalent, 3 different, 4 inconclusive; 1 on bad input or drift of stored
// statistics, 2 on usage errors.
//
// Two triangulations of one input are measured on a common sampling (common/harness/common_sampling.hpp);
// a verdict never rests on metrics that do not see the pattern (api/compare/pattern_checks.hpp).
//
// Apart from that verdict, each arm whose continuous mean is Eq. 5's U is checked against the
// steady mean of the time-discrete model it runs (api/compare/theory_check.hpp): its own section of
// verdict.json ("theory") and a line on stderr, never part of the verdict or the exit code.
//
// Reaction-diffusion scenes (model gray-scott, turing, ...): the same test on their own metric set
// (common/harness/reaction_diffusion_metrics.hpp: each morphogen's mean and variance / mean^2, coverage of
// the preview morphogen above fractions of its range, band shares of its spectrum), each seed a
// system built with that seed, run for the scene's steps: by default the first half is the burn-in
// and the second half is averaged (compare_burn_in / compare_duration override). Their planted
// faults are rd-swap-diffusion and rd-no-feed; stored reference statistics are refused.
//
// Stored reference statistics: `--store-reference FILE --seeds 100` runs only the reference and
// writes its per-seed metrics; `--reference-stats FILE` then replaces the reference arm by them and
// runs a few fresh reference seeds (--reference-seeds, default 3) to detect drift of the stored file
// (a two-sided t test per metric at the Sidak level, see drift_p_value; drift is an error, exit 1).
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// The `--fault` name of the harness's own planted fault: two triangulations compared without their
// common sampling, by mean and coverage alone (a test that the harness rejects a blurred arm must
// fail with it).
inline constexpr const char* kHarnessFault = "harness-mean-and-coverage";

// One comparison, as `physarum compare` takes it from its command line.
struct ComparisonRequest {
  std::string scene;              // the scene file
  std::string device;             // the OpenCL arm's device
  std::vector<std::string> arms;  // "--arm" texts (api/compare/comparison_arms.hpp); none: OpenCL against the reference
  std::optional<int> max_seeds;   // seeds per arm at most (default: the scene's compare_seeds)
  int jobs = 0;                   // worker threads for reference seeds; 0: the cores
  std::string fault;              // a planted fault's name (opencl/planted_faults.hpp), or ""
  std::string out;                // folder for verdict.json, seed_metrics.csv, fields.png, spectra.png; "": none
  std::string reference_stats;    // stored reference metrics instead of the reference arm
  int reference_seeds = 3;        // fresh reference seeds run against reference_stats (drift)
  std::string store_reference;    // run only the reference and store its per-seed metrics here
  // The harness's lines for its user (the surfaces' notes, the theory check, what was not drawn,
  // a stored file's seeds): `physarum compare` prints them on stderr; none: quiet. (The seed
  // progress is drawn on a terminal's stderr only.)
  std::function<void(const std::string&)> log;
};

// What a comparison found: the exit code `physarum compare` gives, verdict.json's content (null after
// --store-reference), and, when fresh reference seeds drifted from stored statistics, the error.
struct ComparisonResult {
  int exit_code = 0;
  nlohmann::ordered_json verdict;
  std::optional<std::string> drift;
};

// The comparison, in-process: writes `out` when asked; InputError on bad input, UsageError on a
// request that cannot be compared (nothing runs then).
ComparisonResult compare(const ComparisonRequest& request);

// `physarum compare`: compare(), with the verdict (JSON) printed on stdout; returns the exit code (0
// equivalent, 3 different, 4 inconclusive; 0 after storing reference statistics). InputError on
// drift of stored statistics, after the verdict.
int run_comparison(const ComparisonRequest& request);

}  // namespace physarum
