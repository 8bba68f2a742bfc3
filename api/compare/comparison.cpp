// The differential harness (`physarum compare`, api/comparison.hpp): arms, seeds in batches, the
// group-sequential test, the theory check, the verdict and its folder.
#include "common/base/atomic_write.hpp"
#include "common/harness/comparison_metrics.hpp"
#include "common/harness/equivalence_test.hpp"
#include "common/base/errors.hpp"
#include "common/scene/scene.hpp"
#include "common/scene/scene_json.hpp"
#include "common/harness/sequential_equivalence.hpp"
#include "opencl/planted_faults.hpp"
#include "api/comparison.hpp"
#include "api/compare/comparison_arms.hpp"
#include "api/compare/comparison_model.hpp"
#include "api/compare/comparison_plot.hpp"
#include "api/compare/pattern_checks.hpp"
#include "api/compare/seed_runner.hpp"
#include "api/compare/theory_check.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>
#include <unistd.h>

namespace physarum {
namespace {


constexpr int kStoredSeeds = 100;  // --store-reference without --seeds

constexpr double kFamilyAlpha = 0.05;  // each kind of false verdict (equivalent, different) at most this often
// Seeds per arm between two looks: enough that the first look has a usable spread, few enough that
// an easy verdict comes after a handful of batches.
constexpr int kBatch = 8;

using Matrix = std::vector<std::vector<double>>;  // [seed][metric]

std::vector<double> column(const Matrix& m, size_t j) {
  std::vector<double> c;
  c.reserve(m.size());
  for (const auto& row : m) c.push_back(row[j]);
  return c;
}

// ---- stored reference statistics ----

// The parameters a stored file must match: everything but the seed, and the mesh by file name
// (the folder differs between checkouts).
nlohmann::ordered_json comparable_parameters(const Scene& scene) {
  nlohmann::ordered_json p = scene_parameters_json(scene);
  p.erase("seed");
  p["mesh"] = std::filesystem::path(scene.mesh).filename().string();
  const ComparisonSettings& c = scene.comparison;
  p["compare"] = {{"burn_in", c.burn_in}, {"duration", c.duration}, {"sample_interval", c.sample_interval},
                  {"bands", c.spectrum_bands}, {"eigenpairs", c.eigenpairs}};
  return p;
}

std::vector<std::string> metric_names(const std::vector<MetricInfo>& metrics) {
  std::vector<std::string> names;
  for (const MetricInfo& m : metrics) names.push_back(m.name);
  return names;
}

void store_reference(const std::string& path, const Scene& scene, const std::vector<MetricInfo>& metrics,
                     const Matrix& values) {
  nlohmann::ordered_json j;
  j["generated_by"] = "physarum compare --store-reference";
  j["parameters"] = comparable_parameters(scene);
  j["metrics"] = metric_names(metrics);
  j["values"] = values;
  write_text_file_atomically(path, j.dump(1) + "\n");
}

Matrix load_reference(const std::string& path, const Scene& scene, const std::vector<MetricInfo>& metrics) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the stored reference statistics");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": malformed stored reference statistics: " + e.what());
  }
  const std::string regenerate = " (regenerate it: physarum compare " + scene.source + " --store-reference " + path +
                                 " --seeds 100)";
  if (!j.contains("parameters") || j["parameters"] != nlohmann::json(comparable_parameters(scene)))
    throw InputError(path + ": stored for other scene parameters than " + scene.source + regenerate);
  if (!j.contains("metrics") || j["metrics"] != nlohmann::json(metric_names(metrics)))
    throw InputError(path + ": stored with other metrics than this build measures" + regenerate);
  Matrix values = j.at("values").get<Matrix>();
  for (const auto& row : values)
    if (row.size() != metrics.size()) throw InputError(path + ": a row has the wrong length" + regenerate);
  if (values.size() < 2) throw InputError(path + ": fewer than 2 stored seeds" + regenerate);
  return values;
}

// Drift: are a few fresh reference seeds drawn from the distribution the stored seeds sample? A
// two-sided t test of the fresh mean against the stored mean with the STORED spread (100 seeds
// estimate it well; the spread of 2 or 3 fresh seeds does not, and a Welch test on it calls drift
// whenever the fresh seeds happen to lie close together). df = stored seeds - 1.
double drift_p_value(const std::vector<double>& fresh, const std::vector<double>& stored) {
  const SampleSummary f = summarize_samples(fresh), s = summarize_samples(stored);
  const double se = s.sd * std::sqrt(1.0 / f.n + 1.0 / s.n);
  if (!(se > 0.0)) return f.mean == s.mean ? 1.0 : 0.0;
  return 2.0 * (1.0 - student_t_cdf(std::abs(f.mean - s.mean) / se, s.n - 1));
}

// ---- running and judging ----

// Progress on stderr, only when it is a terminal (quiet in logs and tests).
bool show_progress() { return ::isatty(STDERR_FILENO) == 1; }

std::string duration_text(double seconds) {
  char text[32];
  if (seconds < 90) std::snprintf(text, sizeof text, "%.0f s", seconds);
  else std::snprintf(text, sizeof text, "%.0f min", seconds / 60.0);
  return text;
}

// Runs the tasks and appends each arm's results to its matrix.
void run_batch(const std::vector<Arm>& arms, const std::vector<SeedTask>& tasks, int jobs, std::vector<Matrix*> into,
               const std::string& what) {
  const auto results = run_seed_tasks(arms, tasks, jobs, [&](int done) {
    if (show_progress())
      std::cerr << "\rphysarum compare: " << what << ": seed " << done << "/" << tasks.size() << "   " << std::flush;
  });
  for (size_t t = 0; t < tasks.size(); ++t) into[static_cast<size_t>(tasks[t].arm)]->push_back(results[t]);
}

std::vector<SeedTask> tasks_for(int arm, int first, int end) {
  std::vector<SeedTask> tasks;
  for (int i = first; i < end; ++i) tasks.push_back({arm, i});
  return tasks;
}

// The arms' per-metric summaries and the margins (absolute, or relative to the second arm's mean).
struct Look {
  std::vector<SampleSummary> a, b;
  std::vector<double> margins;
};

Look summarise(const std::vector<MetricInfo>& info, const Matrix& a, const Matrix& b) {
  Look look;
  for (size_t j = 0; j < info.size(); ++j) {
    look.a.push_back(summarize_samples(column(a, j)));
    look.b.push_back(summarize_samples(column(b, j)));
    const double scale = info[j].kind == MarginKind::Absolute ? 1.0 : std::abs(look.b.back().mean);
    look.margins.push_back(info[j].margin * scale);
  }
  return look;
}

std::string progress_summary(const SequentialEquivalence& test, const std::vector<std::string>& names) {
  int equivalent = 0, different = 0;
  std::string open;
  for (size_t j = 0; j < test.metrics().size(); ++j) {
    const Verdict v = test.metrics()[j].verdict;
    if (v == Verdict::Equivalent) ++equivalent;
    else if (v == Verdict::Different) ++different;
    else open += (open.empty() ? "" : ", ") + names[j];
  }
  return std::to_string(equivalent) + " equivalent, " + std::to_string(different) + " different" +
         (open.empty() ? "" : ", open: " + open);
}

nlohmann::ordered_json metric_row(const std::string& name, const MetricInfo* info, const MetricLook& m,
                                  const std::string& label_a, const std::string& label_b) {
  nlohmann::ordered_json row;
  row["name"] = name;
  row["verdict"] = to_string(m.verdict);
  row["pass"] = m.verdict == Verdict::Equivalent;
  row[label_a + "_mean"] = m.a.mean;
  row[label_b + "_mean"] = m.b.mean;
  row[label_a + "_sd"] = m.a.sd;
  row[label_b + "_sd"] = m.b.sd;
  row["margin"] = m.margin;
  row["margin_kind"] = !info || info->kind == MarginKind::Absolute ? "absolute" : "relative";
  row["difference"] = m.difference;
  row["confidence_interval"] = {m.ci_low, m.ci_high};
  row["level"] = m.level;
  row["decided_at_look"] = m.decided_at_look;
  row["p_value"] = m.p_equivalent;
  row["p_different"] = m.p_different;
  row["achieved_power"] = m.achieved_power;
  if (m.verdict != Verdict::Equivalent && m.verdict != Verdict::Different)
    row["seeds_per_arm_to_settle"] = m.seeds_to_settle;
  return row;
}

int exit_code(Verdict v) {
  switch (v) {
    case Verdict::Equivalent: return 0;
    case Verdict::Different: return 3;
    default: return 4;
  }
}

// What this harness cannot do, refused before anything runs.
void refuse_what_cannot_be_compared(const ComparisonRequest& o) {
  if (o.max_seeds && *o.max_seeds < 2) throw UsageError("--max-seeds (--seeds) must be >= 2");
  if (o.reference_seeds < 2) throw UsageError("--reference-seeds must be >= 2");
  if (o.jobs < 0) throw UsageError("--jobs must be >= 1");
  if (!o.store_reference.empty() && (!o.reference_stats.empty() || !o.fault.empty() || !o.arms.empty()))
    throw UsageError("--store-reference runs only the reference: it takes neither --reference-stats, --fault nor --arm");
  if (!o.reference_stats.empty() && !o.arms.empty())
    throw UsageError("--reference-stats replaces the reference arm: it does not go with --arm");
  const Scene scene = load_scene(o.scene);
  const ComparisonModel& model = comparison_model_of(scene, o.scene);
  // A planted fault of the other model would change nothing, and the harness would rightly call
  // the arms equivalent: a power check that proves nothing.
  if (o.fault == kHarnessFault) {
    if (o.arms.size() != 2)
      throw UsageError(std::string("--fault ") + kHarnessFault + " is a fault of the comparison of two triangulations: "
                       "give two --arm (it would change nothing)");
    return;
  }
  if (!o.fault.empty() && !model.owns_fault(o.fault))
    throw UsageError("--fault " + o.fault + ": not a fault of this model, and " + o.scene + " is " + model.scenes +
                     " (it would change nothing)");
  if (model.refuse) model.refuse(o, scene);
}

// The seeds of both arms (the second stored, or run here batch by batch beside the first) and the
// sequential test that judged them.
struct SequentialRun {
  Matrix a_values, b_values, fresh_reference;
  std::vector<std::string> names;
  int max_seeds = 0;
  SequentialEquivalence test{1, 0.05, 2};
  Verdict verdict = Verdict::Continue;
  // Pattern-scale metrics the coarser of two triangulations cannot represent (api/compare/pattern_checks.hpp).
  std::vector<UnrepresentedScale> unrepresented;
  std::string reason;  // why the verdict is not the sequential test's, when it is not
};

SequentialRun run_sequential_test(const ComparisonRequest& o, const std::vector<Arm>& arms, int jobs) {
  const Arm &A = arms[0], &B = arms[1];
  SequentialRun r;
  r.names = metric_names(A.metrics);
  r.max_seeds = o.max_seeds.value_or(A.scene.comparison.max_seeds);
  const bool stored = !o.reference_stats.empty();
  if (stored) {
    r.b_values = load_reference(o.reference_stats, B.scene, B.metrics);
    // The looks count the smaller arm: past the stored seeds more OpenCL seeds add no information.
    if (r.max_seeds > static_cast<int>(r.b_values.size())) {
      r.max_seeds = static_cast<int>(r.b_values.size());
      if (o.log)
        o.log("physarum compare: at most " + std::to_string(r.max_seeds) + " seeds per arm, as many as " +
              o.reference_stats + " holds");
    }
  }
  r.test = SequentialEquivalence(static_cast<int>(r.names.size()), kFamilyAlpha, r.max_seeds);
  r.test.set_difference_only(difference_only_mask(A.metrics));
  r.unrepresented = unrepresented_scales(arms);
  const auto start = std::chrono::steady_clock::now();
  while (r.verdict == Verdict::Continue) {
    const int n = static_cast<int>(r.a_values.size());
    const int end = std::min(n + kBatch, r.max_seeds);
    std::vector<SeedTask> tasks = tasks_for(0, n, end);
    if (!stored) {
      const std::vector<SeedTask> more = tasks_for(1, n, end);
      tasks.insert(tasks.end(), more.begin(), more.end());
    } else if (n == 0) {
      // Fresh reference seeds the stored file does not hold (it used indices 0 .. stored - 1).
      const int first = static_cast<int>(r.b_values.size());
      const std::vector<SeedTask> more = tasks_for(1, first, first + o.reference_seeds);
      tasks.insert(tasks.end(), more.begin(), more.end());
    }
    run_batch(arms, tasks, jobs, {&r.a_values, stored ? &r.fresh_reference : &r.b_values},
              "look " + std::to_string(r.test.looks() + 1));
    const Look look = summarise(A.metrics, r.a_values, r.b_values);
    r.verdict = r.test.look(look.a, look.b, look.margins);
    if (judge_unrepresented(r.unrepresented, arms, r.a_values, r.b_values)) {
      r.verdict = Verdict::Different;
      r.reason = "a pattern-scale metric is at a scale the coarser arm's triangulation cannot represent, and the finer "
                 "arm has power there (see \"resolution\")";
    }
    if (show_progress()) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const int done = static_cast<int>(r.a_values.size());
      std::cerr << "\rphysarum compare: look " << r.test.looks() << ", " << done << "/" << r.max_seeds
                << " seeds per arm: " << to_string(r.verdict) << " (" << progress_summary(r.test, r.names) << ")";
      if (r.verdict == Verdict::Continue)
        std::cerr << ", at most " << duration_text(elapsed / done * (r.max_seeds - done)) << " more";
      std::cerr << "\n";
    }
  }
  if (r.verdict == Verdict::Equivalent && !examines_pattern(A.metrics)) {
    r.verdict = Verdict::Inconclusive;
    r.reason = "no metric examined the pattern at a scale both arms resolve (every detail energy and band is left out, "
               "see \"left_out\", or difference-only); mean and coverage alone are kept by a blurred pattern";
  }
  return r;
}

// Drift of stored statistics: fresh reference seeds against the stored ones, one row per metric.
nlohmann::ordered_json drift_rows(const std::vector<MetricInfo>& info, const SequentialRun& r, bool& drift) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  const double alpha = sidak_alpha(kFamilyAlpha, static_cast<int>(info.size()));
  for (size_t j = 0; j < info.size(); ++j) {
    const double p = drift_p_value(column(r.fresh_reference, j), column(r.b_values, j));
    drift = drift || p < alpha;
    rows.push_back({{"name", info[j].name}, {"p_value", p}, {"drift", p < alpha}});
  }
  return rows;
}

// What each arm ran: backend, device, surface, and for reaction-diffusion arms the system.
nlohmann::ordered_json arm_list(const std::vector<Arm>& arms) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const Arm& arm : arms) {
    nlohmann::ordered_json a = {{"label", arm.label},
                                {"backend", to_string(arm.backend)},
                                {"device", arm.compute ? arm.compute->device.describe() : "host"},
                                {"faces", arm.surface->domain.face_count},
                                {"time_step", arm.scene.time_step}};
    comparison_model_of(arm.scene, arm.scene.source).describe_arm(arm, a);
    list.push_back(a);
  }
  return list;
}

nlohmann::ordered_json verdict_report(const ComparisonRequest& o, const std::vector<Arm>& arms, const SequentialRun& r,
                                      const std::vector<TheoryRow>& theory, int jobs, double seconds, bool& drift) {
  const Arm &A = arms[0], &B = arms[1];
  const bool stored = !o.reference_stats.empty();
  nlohmann::ordered_json rows = nlohmann::ordered_json::array(), unsettled = nlohmann::ordered_json::array();
  for (size_t j = 0; j < r.names.size(); ++j) {
    const MetricLook& m = r.test.metrics()[j];
    rows.push_back(metric_row(r.names[j], &A.metrics[j], m, A.label, B.label));
    if (A.metrics[j].pattern_scale()) rows.back()["scale"] = A.metrics[j].scale;
    if (A.metrics[j].difference_only)
      rows.back()["difference_only"] = "only the finer arm resolves this scale: it can show a difference, and an "
                                       "equivalent verdict rests on the other metrics";
    for (const UnrepresentedScale& u : r.unrepresented)
      if (u.metric == j && u.decides) {
        rows.back()["statistical_verdict"] = rows.back()["verdict"];
        rows.back()["verdict"] = "different";
        rows.back()["pass"] = false;
        rows.back()["reason"] = u.reason;
      }
    if (m.verdict != Verdict::Equivalent && m.verdict != Verdict::Different)
      unsettled.push_back({{"name", r.names[j]}, {"seeds_per_arm_to_settle", m.seeds_to_settle},
                           {"achieved_power", m.achieved_power}});
  }
  const nlohmann::ordered_json drifted = stored ? drift_rows(A.metrics, r, drift) : nlohmann::ordered_json();

  nlohmann::ordered_json report;
  report["verdict"] = to_string(r.verdict);
  if (!r.reason.empty()) report["reason"] = r.reason;
  report["equivalent"] = r.verdict == Verdict::Equivalent && !drift;
  report["scene"] = o.scene;
  if (const ComparisonModel& model = comparison_model_of(A.scene, o.scene); model.describe_run) model.describe_run(A, report);
  report["arms"] = arm_list(arms);
  report["seeds"] = {{A.label, r.a_values.size()}, {B.label, r.b_values.size()}};
  report["fault"] = o.fault.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(o.fault);
  report["sequential"] = {{"family_alpha", kFamilyAlpha},
                          {"alpha_spending", "O'Brien-Fleming (Lan-DeMets), union bound over the looks"},
                          {"batch", kBatch},
                          {"max_seeds", r.max_seeds},
                          {"looks", r.test.looks()},
                          {"alpha_spent", r.test.alpha_spent()}};
  // How this run went (the rest of the report is the same whatever the threads and the machine's load).
  report["run"] = {{"jobs", jobs}, {"seconds", seconds}};
  report["left_out"] = A.left_out;
  if (!r.unrepresented.empty()) {
    nlohmann::ordered_json resolution = nlohmann::ordered_json::array();
    for (const UnrepresentedScale& u : r.unrepresented) resolution.push_back(u.reason);
    report["resolution"] = resolution;
  }
  if (!unsettled.empty()) report["unsettled"] = unsettled;
  report["reference_source"] = stored ? o.reference_stats : "run here";
  if (stored) report["drift"] = {{"fresh_reference_seeds", r.fresh_reference.size()}, {"drift", drift}, {"metrics", drifted}};
  report["metrics"] = rows;
  report["theory"] = theory_json(theory);
  return report;
}

// DIR/verdict.json, DIR/seed_metrics.csv, DIR/fields.png (api/compare/comparison_fields.hpp) and, when
// there are spectral bands to draw, DIR/spectra.png.
void write_compare_folder(const std::string& folder, const ComparisonRequest& o, const std::string& verdict_text, const std::vector<Arm>& arms,
                          const SequentialRun& r) {
  const Arm &A = arms[0], &B = arms[1];
  create_output_folder(folder);
  const std::filesystem::path out(folder);
  write_text_file_atomically((out / "verdict.json").string(), verdict_text);
  std::ostringstream csv;
  csv << "arm,seed_index";
  for (const MetricInfo& m : A.metrics) csv << "," << m.name;
  csv << "\n";
  csv.precision(17);
  for (const auto& [label, matrix] : {std::pair<std::string, const Matrix*>{B.label, &r.b_values}, {A.label, &r.a_values}})
    for (size_t i = 0; i < matrix->size(); ++i) {
      csv << label << "," << i;
      for (double v : (*matrix)[i]) csv << "," << v;
      csv << "\n";
    }
  write_text_file_atomically((out / "seed_metrics.csv").string(), csv.str());
  // The two patterns the verdict is about, side by side.
  if (!write_comparison_fields((out / "fields.png").string(), arms) && o.log)
    o.log("physarum compare: the arms' fields are uniform; " + (out / "fields.png").string() + " not written");
  // A verdict never turns into bad input: a scene without drawable bands gets no picture, and says so.
  const std::filesystem::path plot = out / "spectra.png";
  if (!write_comparison_plot(plot.string(), metric_names(A.metrics), r.b_values, r.a_values)) {
    std::filesystem::remove(plot);
    if (o.log) o.log("physarum compare: no spectral band power to draw on this scene; " + plot.string() + " not written");
  }
}

}  // namespace

ComparisonResult compare(const ComparisonRequest& o) {
  refuse_what_cannot_be_compared(o);
  const int jobs = o.jobs > 0 ? o.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));

  ArmsRequest request;
  request.scene_path = o.scene;
  for (const std::string& a : o.arms) request.arms.push_back(parse_arm(a));
  request.device = o.device;
  request.withhold_common_sampling = o.fault == kHarnessFault;
  request.keep_fields = !o.out.empty();
  if (!request.withhold_common_sampling)
    request.fault_build_option = opencl::fault_build_option(o.fault);  // UsageError on an unknown name
  request.reference_only = !o.store_reference.empty();
  request.log = o.log;
  const std::vector<Arm> arms = make_arms(request);

  if (!o.store_reference.empty()) {
    Matrix values;
    const int seeds = o.max_seeds.value_or(kStoredSeeds);
    run_batch(arms, tasks_for(0, 0, seeds), jobs, {&values}, "reference");
    if (show_progress()) std::cerr << "\n";
    store_reference(o.store_reference, arms[0].scene, arms[0].metrics, values);
    if (o.log) o.log("physarum compare: stored " + std::to_string(seeds) + " reference seeds of " + o.scene + " in " +
                     o.store_reference);
    return ComparisonResult{};
  }

  const auto start = std::chrono::steady_clock::now();
  const SequentialRun r = run_sequential_test(o, arms, jobs);
  const std::vector<TheoryRow> theory = check_against_theory({&arms[0], &arms[1]}, {&r.a_values, &r.b_values}, kFamilyAlpha);
  auto say = [&](const std::string& line) {
    if (o.log) o.log(line);
  };
  for (const TheoryRow& row : theory) say(theory_line(row));
  for (const UnrepresentedScale& u : r.unrepresented)
    if (u.decides) say("physarum compare: different: " + u.reason);
  if (!r.reason.empty() && r.verdict == Verdict::Inconclusive) say("physarum compare: inconclusive: " + r.reason);
  bool drift = false;
  ComparisonResult result;
  result.verdict =
      verdict_report(o, arms, r, theory, jobs, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), drift);
  if (!o.out.empty()) write_compare_folder(o.out, o, result.verdict.dump(2) + "\n", arms, r);
  if (drift)
    result.drift = o.reference_stats + ": the fresh reference seeds differ from the stored statistics (see \"drift\" "
                   "above); the reference changed: regenerate the file with --store-reference";
  result.exit_code = exit_code(r.verdict);
  return result;
}

int run_comparison(const ComparisonRequest& request) {
  ComparisonRequest o = request;
  if (!o.log) o.log = [](const std::string& line) { std::cerr << line << "\n"; };
  const ComparisonResult result = compare(o);
  if (!result.verdict.is_null()) std::cout << result.verdict.dump(2) << "\n";
  if (result.drift) throw InputError(*result.drift);
  return result.exit_code;
}

}  // namespace physarum
