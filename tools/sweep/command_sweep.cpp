// `physarum sweep SCENE.json --vary KEY=V1,V2,... [--vary ...] | --csv ROWS.csv [--seeds N] [--out DIR]
//  [run options] [--run [--jobs J]] [--emit slurm|parallel]`, `physarum sweep DIR --run | --emit ... |
//  --job I`, and `physarum sweep --collect DIR`: parameter studies as ensembles of independent runs.
//
// Planning writes DIR/sweep.json, DIR/jobs.jsonl and the frozen inputs DIR/inputs (tools/sweep/sweep_plan.hpp,
// tools/sweep/frozen_inputs.hpp); --run executes the jobs here on a pool of processes
// (tools/sweep/sweep_pool.hpp), skipping finished ones, so running it again resumes; --emit writes the
// same list for a cluster: DIR/sweep.slurm, a Slurm array job whose task i runs job i
// (`physarum sweep DIR --job $SLURM_ARRAY_TASK_ID`, tools/sweep/slurm_script.hpp), or DIR/jobs.txt, one
// `physarum sweep . --job I` per line for GNU parallel run in DIR. Every way of running a job checks the
// frozen inputs, skips a finished run, resumes a stopped one from its checkpoint and writes the run's
// output to DIR/logs/run_NNNN.log. The runs share nothing but their output folders. --collect writes
// DIR/sweep.csv and DIR/contact_sheet.png (tools/sweep/sweep_collect.hpp).
#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"
#include "opencl/runtime/device_selection.hpp"
#include "tools/commands.hpp"
#include "tools/sweep/sweep_collect.hpp"
#include "tools/sweep/slurm_script.hpp"
#include "tools/sweep/sweep_plan.hpp"
#include "tools/sweep/sweep_pool.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>
#include <unistd.h>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;

struct SweepOptions {
  std::string target;  // SCENE.json (plan a sweep) or DIR (an existing sweep)
  std::vector<std::string> vary;
  std::string csv;
  int seeds = 1;
  std::string out = "sweep";
  bool run = false;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::string> emit;
  std::string collect;
  std::optional<int> job;
  int thumbnail = 160;
  // Passed to every `physarum run`.
  std::optional<long long> steps;
  std::optional<double> sim_time;
  std::string backend;
  std::string device;
  std::optional<double> checkpoint_every;
  std::optional<int> texture_size;
  std::string texture_format;
  SlurmOptions slurm;  // --emit slurm's
};

std::vector<std::string> run_options(const SweepOptions& o) {
  std::vector<std::string> args;
  if (o.steps) args.insert(args.end(), {"--steps", std::to_string(*o.steps)});
  if (o.sim_time) args.insert(args.end(), {"--sim-time", nlohmann::json(*o.sim_time).dump()});
  if (!o.backend.empty()) args.insert(args.end(), {"--backend", o.backend});
  if (!o.device.empty()) args.insert(args.end(), {"--device", o.device});
  if (o.checkpoint_every) args.insert(args.end(), {"--checkpoint-every", nlohmann::json(*o.checkpoint_every).dump()});
  if (o.texture_size) args.insert(args.end(), {"--texture-size", std::to_string(*o.texture_size)});
  if (!o.texture_format.empty()) args.insert(args.end(), {"--texture-format", o.texture_format});
  return args;
}

// One job per line, for `cd DIR && parallel < jobs.txt`: each line is `physarum sweep . --job I`, so a
// line skips a finished run and resumes a stopped one exactly as a Slurm task does, and the file
// names no folder: moved or copied with it, it runs the jobs of the copy it is run in.
void write_parallel_file(const SweepPlan& plan, const std::vector<SweepJob>& jobs) {
  std::string text;
  const std::string exe = this_executable();
  for (const SweepJob& job : jobs) text += shell_command({exe, "sweep", ".", "--job", std::to_string(job.index)}) + "\n";
  write_text_file_atomically((fs::path(plan.folder) / "jobs.txt").string(), text);
}

// OpenCL devices to spread jobs over: every device when there are several, none otherwise (one
// device, or none: the runs choose their own).
std::vector<int> devices_to_spread() {
  try {
    const auto devices = opencl::list_devices();
    if (devices.size() < 2) return {};
    std::vector<int> indices;
    for (const auto& d : devices) indices.push_back(d.index);
    return indices;
  } catch (const DeviceError&) {
    return {};
  }
}

// One job, in the sweep folder wherever it is now, its output into DIR/logs/run_NNNN.log.
int run_job(const std::string& target, int index) {
  const SweepPlan plan = read_sweep_plan(target);
  const std::vector<SweepJob> jobs = read_sweep_jobs(plan.folder);
  if (index < 0 || index >= static_cast<int>(jobs.size()))
    throw UsageError("--job " + std::to_string(index) + ": " + plan.folder + " has jobs 0.." + std::to_string(jobs.size() - 1));
  const SweepJob& job = jobs[static_cast<std::size_t>(index)];
  if (job.finished()) {
    std::cout << "physarum sweep: job " << index << " finished before (" << job.out << "/run.json): skipped\n";
    return 0;
  }
  check_frozen_inputs(plan.inputs, plan.folder);
  std::cout << "physarum sweep: job " << index << (job.resumes() ? " resumes from its checkpoint" : " starts") << " in "
            << job.out << "; its log: " << job_log_path(plan.folder, index) << "\n";
  // The job becomes the run itself: its exit code and signals are the scheduler's to see.
  std::vector<std::string> words{this_executable()};
  const std::vector<std::string> args = job.run_args();
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::cout.flush();
  const int log = open_job_log(plan.folder, job);
  if (::dup2(log, STDOUT_FILENO) < 0 || ::dup2(log, STDERR_FILENO) < 0 || ::chdir(plan.folder.c_str()) != 0)
    throw InputError("physarum sweep: cannot start job " + std::to_string(index) + " in " + plan.folder);
  ::execv(words[0].c_str(), argv.data());
  throw InputError("physarum sweep: cannot run " + words[0] + " for job " + std::to_string(index));
}

int run_sweep(const SweepOptions& o) {
  if (!o.collect.empty()) {
    if (!o.target.empty() || o.run || !o.emit.empty() || o.job) throw UsageError("--collect DIR takes no other target or action");
    const SweepCollection c = collect_sweep(o.collect, o.thumbnail);
    std::cout << "physarum sweep: collected " << c.rows << " runs (" << c.missing << " missing) into " << o.collect
              << "/sweep.csv and " << o.collect << "/contact_sheet.png (" << c.layout.rows << " x " << c.layout.columns
              << " cells of " << c.layout.seeds << " seeds, " << c.layout.width() << " x " << c.layout.height() << " px)\n";
    // A partial sweep is collected (its sheet is worth a look) but is not a success.
    auto list = [](const std::vector<int>& jobs) {
      std::string s;
      for (const int i : jobs) s += " " + std::to_string(i);
      return s;
    };
    if (!c.failed_jobs.empty())
      std::cerr << "physarum sweep: failed or unfinished jobs (folder without run.json; logs in " << o.collect
                << "/logs/):" << list(c.failed_jobs) << "\n";
    if (!c.missing_jobs.empty()) std::cerr << "physarum sweep: jobs never run:" << list(c.missing_jobs) << "\n";
    return c.missing > 0 ? 1 : 0;
  }
  if (o.target.empty()) throw UsageError("give a scene file to plan a sweep, a sweep folder, or --collect DIR");
  const bool slurm_options = o.slurm.max_array || !o.slurm.sbatch.empty() || !o.slurm.prologue.empty() || o.slurm.gpu;
  if (slurm_options && std::find(o.emit.begin(), o.emit.end(), "slurm") == o.emit.end())
    throw UsageError("--max-array, --sbatch, --prologue and --gpu shape the Slurm scripts: give them with --emit slurm");
  if (!o.slurm.prologue.empty() && !std::ifstream(o.slurm.prologue))
    throw UsageError("--prologue " + o.slurm.prologue + ": cannot read the file");
  const bool planning = !o.vary.empty() || !o.csv.empty();
  if (o.job) {
    if (planning || o.run || !o.emit.empty()) throw UsageError("--job I runs one job of an existing sweep folder and nothing else");
    return run_job(o.target, *o.job);
  }

  SweepPlan plan;
  if (fs::is_directory(o.target)) {
    if (planning || !run_options(o).empty())
      throw UsageError(o.target + " is a sweep folder: its variants and run options are fixed in its sweep.json "
                                  "(plan a new sweep from a scene file)");
    plan = read_sweep_plan(o.target);
  } else {
    plan = make_sweep_plan(o.target, o.vary, o.csv, o.seeds, run_options(o), o.out);
    check_sweep_variants(plan);
    write_sweep_plan(plan);
  }
  const std::vector<SweepJob> jobs = read_sweep_jobs(plan.folder);
  if (jobs.empty()) throw InputError(plan.folder + ": the sweep has no jobs");
  std::cout << "physarum sweep: " << jobs.size() << " runs (" << plan.variant_count() << " variants x " << plan.seeds.size()
            << " seeds) in " << plan.folder << "/jobs.jsonl\n";
  for (const std::string& e : o.emit) {
    if (e == "slurm") {
      const std::vector<std::string> scripts = write_slurm_scripts(plan, static_cast<int>(jobs.size()), o.slurm);
      for (const std::string& script : scripts) std::cout << "physarum sweep: wrote " << script << " (sbatch it)\n";
    } else {
      write_parallel_file(plan, jobs);
      std::cout << "physarum sweep: wrote " << plan.folder << "/jobs.txt (cd " << shell_command({plan.folder})
                << " && parallel < jobs.txt)\n";
    }
  }
  if (!o.run) return 0;
  check_frozen_inputs(plan.inputs, plan.folder);
  const SweepPoolReport r = run_sweep_jobs(plan.folder, jobs, o.jobs, devices_to_spread());
  std::cout << "physarum sweep: ran " << r.ran << ", skipped " << r.skipped << " finished, " << r.failed.size()
            << " failed, in " << r.seconds << " s with " << o.jobs << " workers\n";
  if (!r.failed.empty()) {
    std::cerr << "physarum sweep: failed jobs:";
    for (const int i : r.failed) std::cerr << " " << i;
    std::cerr << " (logs in " << plan.folder << "/logs/; run the sweep again to retry them)\n";
    return 1;
  }
  return 0;
}

}  // namespace

Command add_sweep_command(CLI::App& parent) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* app = parent.add_subcommand(
      "sweep",
      "Parameter sweeps: plan them, run them here or on a cluster, collect the results\n"
      "Parameter sweeps: expand a scene's variants (--vary grids or --csv rows) x seeds into DIR/jobs.jsonl, run "
      "them here on a pool of processes (--run, resumable), or write them for a cluster (--emit slurm: DIR/sweep.slurm; "
      "--emit parallel: DIR/jobs.txt); --collect DIR gathers DIR/sweep.csv and DIR/contact_sheet.png. Example: "
      "physarum sweep tools/scenes/default.json --vary turn_rate=90,180,360 --vary sensor_angle=22.5,45 --seeds 2 "
      "--steps 300 --out sweep --run && physarum sweep --collect sweep");
  app->footer("Exit codes: 0 success, 1 bad input, a failed job (the others still run) or --collect with runs missing "
              "or failed, 2 usage error.");
  app->add_option("target", options->target,
                  "A scene file (plans a sweep into --out) or an existing sweep folder (--run, --emit, --job)");
  app->add_option("--vary", options->vary,
                  "KEY=V1,V2,... (repeatable): every combination of the values is a variant. KEY as run --set takes "
                  "it, nested with dots (maps.ramp.range=[0,1],[0.5,1.5]); values are JSON where they parse");
  app->add_option("--csv", options->csv,
                  "A CSV of variants instead of a grid: the first line names the keys, each row is one variant");
  app->add_option("--seeds", options->seeds, "Runs per variant, seeded the scene's seed, +1, +2, ...")->capture_default_str();
  app->add_option("--out", options->out, "The sweep folder (one run_NNNN folder per job inside)")->capture_default_str();
  app->add_flag("--run", options->run, "Run the jobs here, skipping finished ones (run.json present)");
  app->add_option("--jobs", options->jobs, "Processes in parallel for --run (default: the cores)")->capture_default_str();
  app->add_option("--emit", options->emit, "Write the jobs for a cluster: slurm (DIR/sweep.slurm), parallel (DIR/jobs.txt)")
      ->check(CLI::IsMember({"slurm", "parallel"}));
  app->add_option("--max-array", options->slurm.max_array,
                  "With --emit slurm: tasks per array at most (default: the site's MaxArraySize from scontrol, else "
                  "1001); more jobs are written as sweep_0.slurm, sweep_1.slurm, ...");
  app->add_option("--sbatch", options->slurm.sbatch,
                  "With --emit slurm: an extra #SBATCH line, e.g. --sbatch \"--time=01:00:00\" (repeatable: --mem, "
                  "--partition, --account, ...)");
  app->add_option("--prologue", options->slurm.prologue,
                  "With --emit slurm: a file whose lines run before each job (module load, environment)");
  app->add_flag("--gpu", options->slurm.gpu, "With --emit slurm: ask for one GPU per task (--gres=gpu:1)");
  app->add_option("--collect", options->collect, "Gather DIR's runs into DIR/sweep.csv and DIR/contact_sheet.png");
  app->add_option("--job", options->job, "Run job I of the sweep folder (what each Slurm array task does)");
  app->add_option("--thumbnail", options->thumbnail, "Side of a contact-sheet thumbnail, in pixels")->capture_default_str();
  app->add_option("--steps", options->steps, "For every run: number of time steps");
  app->add_option("--sim-time", options->sim_time, "For every run: simulated seconds");
  app->add_option("--backend", options->backend, "For every run: auto, reference or opencl")
      ->check(CLI::IsMember({"auto", "reference", "opencl"}));
  app->add_option("--device", options->device, "For every run: the OpenCL device (default: spread over the devices)");
  app->add_option("--checkpoint-every", options->checkpoint_every, "For every run: checkpoint every T simulated seconds");
  app->add_option("--texture-size", options->texture_size, "For every run: the baked texture's side in texels");
  app->add_option("--texture-format", options->texture_format, "For every run: png, png16 or exr")
      ->check(CLI::IsMember({"png", "png16", "exr"}));
  return Command{app, [options] { return run_sweep(*options); }};
}

}  // namespace physarum::cli
