#pragma once
// A parameter sweep as a list of independent runs (`physarum sweep`, tools/sweep/command_sweep.cpp): the
// scene's variants (a grid of --vary values, or the rows of a CSV file) times the seeds, each run one
// `physarum run` of its own with the variant as --set overrides (common/scene/scene_overrides.hpp) and its
// own output folder. Written to the sweep folder DIR as
//
//   DIR/sweep.json   what was asked: the scene, the varied keys and their values (or the CSV rows),
//                    the seeds, the options every run gets and the frozen inputs with their hashes;
//                    `--collect` lays its sheet out by it
//   DIR/jobs.jsonl   one JSON object per line, line i = job i: {"index", "overrides", "seed", "out",
//                    "args"}, args being the complete `physarum run` argument list
//   DIR/inputs/      the scene and the files it reads, frozen (tools/sweep/frozen_inputs.hpp)
//
// Every path in them is relative to DIR and every job runs with DIR as its working directory, so the
// folder can be moved or copied and run in its new place.
//
// Jobs are ordered variant by variant, the first varied key slowest, the seeds innermost: job
// index = variant * seeds + seed_index.
#include "tools/sweep/frozen_inputs.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace physarum::cli {

// One varied key and its values (JSON, as --set reads them).
struct SweepAxis {
  std::string key;
  std::vector<nlohmann::json> values;
};

struct SweepJob {
  int index = 0;
  nlohmann::ordered_json overrides = nlohmann::ordered_json::object();  // the variant: KEY -> value
  std::uint32_t seed = 1;
  std::string out;                // absolute (jobs.jsonl holds it relative to the sweep folder)
  std::vector<std::string> args;  // `physarum run` arguments (without the program), paths relative to the folder

  bool finished() const;  // out/run.json exists (a run writes it last)
  // What running the job means now (run in the sweep folder): `run SCENE --resume OUT` when a stopped
  // run left out/checkpoint.bin (preempted, cancelled, killed: it continues bit for bit; the scene
  // given because the folder may have moved since the checkpoint was written), else `args`.
  std::vector<std::string> run_args() const;
  bool resumes() const;  // not finished, and out/checkpoint.bin exists
};

struct SweepPlan {
  std::string scene_source;  // the scene file planned from (absolute); only for planning
  FrozenInputs inputs;       // the frozen scene and the files it reads
  // Grid mode: the varied keys, every combination of their values is a variant. CSV mode (csv_keys
  // not empty): each row of `csv_rows` is a variant, one value per csv_keys entry.
  std::vector<SweepAxis> axes;
  std::vector<std::string> csv_keys;
  std::vector<std::vector<nlohmann::json>> csv_rows;
  std::vector<std::uint32_t> seeds;
  std::vector<std::string> run_options;  // passed to every run (--steps 200, --backend reference, ...)
  std::string folder;  // DIR, absolute

  int variant_count() const;
  // The overrides of variant v (grid: the first axis slowest).
  nlohmann::ordered_json variant(int v) const;
  // Every job, in index order.
  std::vector<SweepJob> jobs() const;
  // The varied keys in order (grid axes or CSV columns).
  std::vector<std::string> varied_keys() const;
};

// Parses "KEY=V1,V2,..." (--vary): values split at commas outside brackets, braces and quotes (so
// maps.ramp.range=[0,1],[0.5,1.5] has two values), each read as JSON where it parses, else a
// string. UsageError naming the flag on an empty key or value, or a key given twice across axes is
// checked by make_sweep_plan.
SweepAxis parse_vary(const std::string& text);

// Reads a CSV of variants: the first line names the keys, each further line is one variant. Fields
// may be double-quoted (a quote inside doubled), so JSON lists fit: "[0.5,1.5]". Blank lines are
// skipped. InputError naming the file and line on a row with the wrong number of fields.
void read_variant_csv(const std::string& path, std::vector<std::string>& keys, std::vector<std::vector<nlohmann::json>>& rows);

// The most jobs one sweep plans (each is a folder and a line of jobs.jsonl; more belongs in several
// sweeps). Checked before the grid is expanded, so a huge --vary is refused at once.
constexpr int kMaxSweepJobs = 100000;

// Builds the plan. `seeds` runs per variant, seeded scene_seed, scene_seed + 1, ... where
// scene_seed is the scene file's "seed" (1 when absent). UsageError when a key is varied twice,
// seeds < 1, there is nothing to run, or the grid has more than kMaxSweepJobs jobs.
SweepPlan make_sweep_plan(const std::string& scene, const std::vector<std::string>& vary, const std::string& csv,
                          int seeds, const std::vector<std::string>& run_options, const std::string& folder);

// Every value of every --vary or CSV column (the strings among them may name files to freeze).
std::vector<nlohmann::json> variant_values(const SweepPlan& plan);

// Reads every variant as a scene (load_scene with its overrides), so a misspelt key or a value out of
// range is refused before any job exists, naming the variant. Cheap: no surface is built.
void check_sweep_variants(const SweepPlan& plan);

// Writes DIR/inputs, DIR/jobs.jsonl and DIR/sweep.json (and creates DIR/logs). A folder that already holds a
// sweep keeps it when it is the same one (so re-running the command resumes) and is refused with
// InputError when it is another.
void write_sweep_plan(const SweepPlan& plan);

// Reads DIR/sweep.json back (InputError naming the file when DIR holds no sweep). DIR is where the
// folder is now, wherever it was planned.
SweepPlan read_sweep_plan(const std::string& folder);

// Reads DIR/jobs.jsonl, the jobs as workers see them (InputError naming the file and line on a
// malformed line).
std::vector<SweepJob> read_sweep_jobs(const std::string& folder);

// A command line for a POSIX shell: every word single-quoted where needed.
std::string shell_command(const std::vector<std::string>& words);

}  // namespace physarum::cli
