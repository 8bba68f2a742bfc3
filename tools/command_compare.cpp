// `physarum compare SCENE.json [--device SPEC] [--seeds N] [--fault NAME] [--out DIR]
//                              [--reference-stats FILE] [--reference-seeds N] [--store-reference FILE]`:
// the differential harness. Runs independent seeds of the reference and the OpenCL backend on one
// scene, time-averages dimensionless pattern metrics per seed after a burn-in
// (common/comparison_metrics.hpp) and decides, metric by metric, whether the two backends are
// equivalent: Welch two one-sided tests (TOST) against the scene's margins, each at the Sidak level
// that keeps the family-wise error at 5 %. Exit 0 when every metric is equivalent, 1 when not (or on
// bad input), 2 on usage errors.
//
// Stored reference statistics: `--store-reference FILE --seeds 100` runs only the reference and
// writes its per-seed metrics; `--reference-stats FILE` then replaces the reference arm by them and
// runs a few fresh reference seeds (--reference-seeds, default 3) to detect drift of the stored file
// (a two-sided t test per metric at the Sidak level, see drift_p_value; drift is an error, exit 1).
//
// Seeds per arm: --seeds, else compare_seeds in the scene, else the power calculation below.
#include "common/atomic_write.hpp"
#include "common/comparison_metrics.hpp"
#include "common/equivalence_test.hpp"
#include "common/errors.hpp"
#include "common/scene.hpp"
#include "common/scene_json.hpp"
#include "common/scene_surface.hpp"
#include "opencl/compute_context.hpp"
#include "opencl/planted_faults.hpp"
#include "opencl/simulation.hpp"
#include "tools/backend_factory.hpp"
#include "tools/commands.hpp"
#include "tools/comparison_plot.hpp"
#include "tools/feasible_surface.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>
#include <unistd.h>

namespace physarum::cli {
namespace {

struct CompareOptions {
  std::string scene;
  std::string device;
  std::optional<int> seeds;
  std::string fault;
  std::string out;
  std::string reference_stats;
  int reference_seeds = 3;
  std::string store_reference;
};

constexpr double kFamilyAlpha = 0.05;  // family-wise error of the whole verdict
// Power of the whole verdict when the backends are truly equal: every metric must pass, so each
// TOST gets power 1 - (1 - kFamilyPower) / metrics (a union bound over the metrics' misses).
constexpr double kFamilyPower = 0.9;
constexpr int kPilotSeeds = 6;         // reference seeds run to estimate the spread when nothing is stored
constexpr int kMinSeeds = 4, kMaxSeeds = 100;
// Seeds of the two arms never overlap: the reference uses scene.seed + kReferenceSeedOffset + i.
constexpr std::uint32_t kReferenceSeedOffset = 100000;

using Matrix = std::vector<std::vector<double>>;  // [seed][metric]

std::vector<double> column(const Matrix& m, size_t j) {
  std::vector<double> c;
  c.reserve(m.size());
  for (const auto& row : m) c.push_back(row[j]);
  return c;
}

// ---- running the arms ----

struct Harness {
  const Scene& scene;
  const SceneSurface& surface;
  const ComparisonMetrics& metrics;
  std::optional<opencl::ComputeContext> compute;
  opencl::OpenCLSimulationOptions opencl_options;

  std::vector<double> reference_seed(std::uint32_t seed) const {
    Scene s = scene;
    s.seed = seed;
    const auto sim = make_backend(BackendChoice::Reference, nullptr, surface.domain, s);
    return metrics.measure_seed(*sim);
  }
  std::vector<double> opencl_seed(std::uint32_t seed) const {
    Scene s = scene;
    s.seed = seed;
    const auto sim = make_backend(BackendChoice::OpenCL, &*compute, surface.domain, s, opencl_options);
    return metrics.measure_seed(*sim);
  }
};

// Progress on stderr, only when it is a terminal (quiet in logs and tests).
void progress(const std::string& what, int done, int total) {
  if (::isatty(STDERR_FILENO) != 1) return;
  std::cerr << "\rphysarum compare: " << what << " seed " << done << "/" << total << "   " << std::flush;
  if (done == total) std::cerr << "\n";
}

Matrix run_reference_seeds(const Harness& h, int first, int count) {
  Matrix m;
  for (int i = 0; i < count; ++i) {
    m.push_back(h.reference_seed(h.scene.seed + kReferenceSeedOffset + static_cast<std::uint32_t>(first + i)));
    progress("reference", i + 1, count);
  }
  return m;
}

Matrix run_opencl_seeds(const Harness& h, int count) {
  Matrix m;
  for (int i = 0; i < count; ++i) {
    m.push_back(h.opencl_seed(h.scene.seed + static_cast<std::uint32_t>(i)));
    progress("opencl", i + 1, count);
  }
  return m;
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

std::vector<std::string> metric_names(const ComparisonMetrics& metrics) {
  std::vector<std::string> names;
  for (const MetricInfo& m : metrics.metrics()) names.push_back(m.name);
  return names;
}

void store_reference(const std::string& path, const Scene& scene, const ComparisonMetrics& metrics,
                     const Matrix& values) {
  nlohmann::ordered_json j;
  j["generated_by"] = "physarum compare --store-reference";
  j["parameters"] = comparable_parameters(scene);
  j["metrics"] = metric_names(metrics);
  j["values"] = values;
  write_text_file_atomically(path, j.dump(1) + "\n");
}

Matrix load_reference(const std::string& path, const Scene& scene, const ComparisonMetrics& metrics) {
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
    if (row.size() != metrics.metrics().size()) throw InputError(path + ": a row has the wrong length" + regenerate);
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

// ---- the verdict ----

int run_compare(const CompareOptions& o) {
  if (o.seeds && *o.seeds < 2) throw UsageError("--seeds must be >= 2");
  if (o.reference_seeds < 2) throw UsageError("--reference-seeds must be >= 2");
  if (!o.store_reference.empty() && (!o.reference_stats.empty() || !o.fault.empty()))
    throw UsageError("--store-reference runs only the reference: it takes neither --reference-stats nor --fault");
  const std::string fault_option = opencl::fault_build_option(o.fault);  // UsageError on an unknown name

  const Scene scene = load_scene(o.scene);
  // Each seed runs burn-in + duration: the run whose work the checks estimate.
  const long long steps_per_seed = std::max<long long>(
      1, std::llround((scene.comparison.burn_in + scene.comparison.duration) / scene.time_step));
  const SceneSurface surface = prepare_feasible_surface(scene, steps_per_seed);
  const ComparisonMetrics metrics(surface, scene);
  const std::vector<MetricInfo>& info = metrics.metrics();
  const int metric_count = static_cast<int>(info.size());
  Harness h{scene, surface, metrics, std::nullopt, {}};

  if (!o.store_reference.empty()) {
    const int n = o.seeds.value_or(100);
    store_reference(o.store_reference, scene, metrics, run_reference_seeds(h, 0, n));
    std::cout << "physarum compare: stored " << n << " reference seeds of " << o.scene << " in " << o.store_reference
              << "\n";
    return 0;
  }

  h.compute = opencl::make_compute_context(o.device);
  h.opencl_options.build_options = fault_option;
  const double alpha = sidak_alpha(kFamilyAlpha, metric_count);

  // ---- the reference arm: stored, or run here (a pilot first, to size both arms) ----
  const bool stored = !o.reference_stats.empty();
  Matrix reference = stored ? load_reference(o.reference_stats, scene, metrics) : run_reference_seeds(h, 0, kPilotSeeds);

  // ---- seeds per arm ----
  // Power calculation: for each metric, the smallest n per arm at which a Welch TOST at level alpha
  // (Sidak) has power `power` when the backends are truly equal, given the reference arm's measured
  // seed-to-seed standard deviation and the metric's margin (tost_seeds_per_arm); the largest over
  // the metrics, clamped to [kMinSeeds, kMaxSeeds].
  const double power = 1.0 - (1.0 - kFamilyPower) / metric_count;
  std::vector<double> margins(info.size());
  int needed = kMinSeeds;
  for (size_t j = 0; j < info.size(); ++j) {
    const SampleSummary r = summarize_samples(column(reference, j));
    margins[j] = info[j].kind == MarginKind::Absolute ? info[j].margin : info[j].margin * std::abs(r.mean);
    if (margins[j] > 0.0) needed = std::max(needed, tost_seeds_per_arm(r.sd, margins[j], alpha, power));
  }
  const bool clamped = needed > kMaxSeeds;
  const int from_power = std::min(needed, kMaxSeeds);
  const int seeds = o.seeds ? *o.seeds : (scene.comparison.seeds > 0 ? scene.comparison.seeds : from_power);

  // ---- run ----
  Matrix fresh_reference;
  if (stored) {
    // Seeds the stored file does not hold (it used indices 0 .. stored - 1).
    fresh_reference = run_reference_seeds(h, static_cast<int>(reference.size()), o.reference_seeds);
  } else if (static_cast<int>(reference.size()) < seeds) {
    Matrix more = run_reference_seeds(h, static_cast<int>(reference.size()), seeds - static_cast<int>(reference.size()));
    reference.insert(reference.end(), more.begin(), more.end());
  }
  const Matrix device = run_opencl_seeds(h, seeds);

  // ---- decide ----
  nlohmann::ordered_json verdict;
  bool equivalent = true;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (size_t j = 0; j < info.size(); ++j) {
    const std::vector<double> r = column(reference, j), d = column(device, j);
    const TostResult t = welch_tost(d, r, margins[j], alpha);
    equivalent = equivalent && t.equivalent;
    nlohmann::ordered_json row;
    row["name"] = info[j].name;
    row["reference_mean"] = t.b.mean;
    row["opencl_mean"] = t.a.mean;
    row["reference_sd"] = t.b.sd;
    row["opencl_sd"] = t.a.sd;
    row["margin"] = margins[j];
    row["margin_kind"] = info[j].kind == MarginKind::Absolute ? "absolute" : "relative";
    row["difference"] = t.difference;
    row["p_lower"] = t.p_lower;
    row["p_upper"] = t.p_upper;
    row["p_value"] = t.p;
    row["pass"] = t.equivalent;
    rows.push_back(row);
  }
  // The analytic check: the OpenCL arm's mean concentration against U of Eq. 5 (a one-sample TOST,
  // the reference value 1 known exactly).
  {
    const std::vector<double> d = column(device, 0);
    const SampleSummary a = summarize_samples(d);
    const TostResult t = welch_tost(a, SampleSummary{a.n, 1.0, 0.0}, margins[0], alpha);
    equivalent = equivalent && t.equivalent;
    rows.push_back({{"name", "mean_over_U_vs_analytic"}, {"reference_mean", 1.0}, {"opencl_mean", a.mean},
                    {"reference_sd", 0.0}, {"opencl_sd", a.sd}, {"margin", margins[0]}, {"margin_kind", "absolute"},
                    {"difference", t.difference}, {"p_lower", t.p_lower}, {"p_upper", t.p_upper}, {"p_value", t.p},
                    {"pass", t.equivalent}});
  }

  // Drift of stored statistics: fresh reference seeds against the stored ones.
  bool drift = false;
  nlohmann::ordered_json drift_rows = nlohmann::ordered_json::array();
  if (stored) {
    for (size_t j = 0; j < info.size(); ++j) {
      const double p = drift_p_value(column(fresh_reference, j), column(reference, j));
      drift = drift || p < alpha;
      drift_rows.push_back({{"name", info[j].name}, {"p_value", p}, {"drift", p < alpha}});
    }
  }

  verdict["equivalent"] = equivalent && !drift;
  verdict["seeds"] = {{"reference", reference.size()}, {"opencl", device.size()}};
  verdict["scene"] = o.scene;
  verdict["device"] = h.compute->device.describe();
  verdict["fault"] = o.fault.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(o.fault);
  verdict["family_alpha"] = kFamilyAlpha;
  verdict["alpha_per_metric"] = alpha;
  verdict["power_calculation"] = {{"family_power", kFamilyPower},
                                  {"power_per_metric", power},
                                  {"seeds_needed", needed},
                                  {"clamped_to", clamped ? nlohmann::ordered_json(kMaxSeeds) : nlohmann::ordered_json()},
                                  {"seeds_used", seeds}};
  verdict["reference_source"] = stored ? o.reference_stats : "run here";
  if (stored) verdict["drift"] = {{"fresh_reference_seeds", fresh_reference.size()}, {"drift", drift}, {"metrics", drift_rows}};
  verdict["metrics"] = rows;
  const std::string text = verdict.dump(2) + "\n";
  std::cout << text;

  if (!o.out.empty()) {
    create_output_folder(o.out);
    const std::filesystem::path out(o.out);
    write_text_file_atomically((out / "verdict.json").string(), text);
    std::ostringstream csv;
    csv << "backend,seed_index";
    for (const MetricInfo& m : info) csv << "," << m.name;
    csv << "\n";
    csv.precision(17);
    for (const auto& [name, matrix] : {std::pair<const char*, const Matrix*>{"reference", &reference}, {"opencl", &device}})
      for (size_t i = 0; i < matrix->size(); ++i) {
        csv << name << "," << i;
        for (double v : (*matrix)[i]) csv << "," << v;
        csv << "\n";
      }
    write_text_file_atomically((out / "seed_metrics.csv").string(), csv.str());
    write_comparison_plot((out / "spectra.png").string(), metric_names(metrics), reference, device);
  }
  if (drift)
    throw InputError(o.reference_stats + ": the fresh reference seeds differ from the stored statistics (see \"drift\" "
                     "above); the reference changed: regenerate the file with --store-reference");
  return equivalent ? 0 : 1;
}

}  // namespace

Command add_compare_command(CLI::App& parent) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* app = parent.add_subcommand(
      "compare",
      "Differential harness: decide whether the OpenCL backend simulates the same thing as the reference "
      "(prints a JSON verdict; exit 0 equivalent, 1 not, 2 usage error)");
  app->add_option("scene", options->scene, "Scene file (JSON); compare_* keys set the run length and margins")
      ->required();
  app->add_option("--device", options->device, "OpenCL device: index from `physarum devices` or a name substring");
  app->add_option("--seeds", options->seeds, "Seeds per arm (default: from the power calculation)");
  std::string faults;
  for (const opencl::PlantedFault& f : opencl::planted_faults()) faults += std::string("\n  ") + f.name + ": " + f.what;
  app->add_option("--fault", options->fault, "Plant a deliberate bug in the OpenCL kernels:" + faults);
  app->add_option("--out", options->out, "Folder for verdict.json, seed_metrics.csv and spectra.png");
  app->add_option("--reference-stats", options->reference_stats,
                  "Stored per-seed reference metrics to use instead of running the reference arm");
  app->add_option("--reference-seeds", options->reference_seeds,
                  "Fresh reference seeds run against --reference-stats to detect drift")
      ->capture_default_str();
  app->add_option("--store-reference", options->store_reference,
                  "Run only the reference (--seeds, default 100) and store its per-seed metrics in this file");
  return Command{app, [options] { return run_compare(*options); }};
}

}  // namespace physarum::cli
