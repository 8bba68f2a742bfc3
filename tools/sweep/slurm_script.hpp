#pragma once
// A sweep as Slurm array jobs (`physarum sweep ... --emit slurm`): task i of an array runs one job
// through `physarum sweep DIR --job I`, which skips a finished run and resumes a stopped one, so a
// script can be submitted again after a preemption or a time limit. A site caps the array indices
// (MaxArraySize, 1001 by default): a sweep of more jobs is written as several scripts, part k's task
// i running job k * max_array + i, so every job is in exactly one array.
#include "tools/sweep/sweep_plan.hpp"

#include <optional>
#include <string>
#include <vector>

namespace physarum::cli {

struct SlurmOptions {
  std::optional<int> max_array;     // tasks per array at most; nullopt: the site's (site_max_array_size)
  std::vector<std::string> sbatch;  // extra "#SBATCH ARGS" lines (--time, --mem, --partition, --account, ...)
  std::string prologue;             // a file whose lines run before the job (module load, environment)
  bool gpu = false;                 // ask for one GPU per task (#SBATCH --gres=gpu:1)
};

// Slurm's default MaxArraySize: array indices 0..1000.
constexpr int kSlurmDefaultMaxArraySize = 1001;

// The site's MaxArraySize from `scontrol show config`; nullopt when scontrol is absent or does not
// say (planning away from the cluster).
std::optional<int> site_max_array_size();

// Writes DIR/sweep.slurm (the sweep in one array) or DIR/sweep_0.slurm, DIR/sweep_1.slurm, ...
// (arrays of at most max_array tasks, by default the site's MaxArraySize, else Slurm's default);
// returns their paths. UsageError on max_array < 1, a max_array past the site's MaxArraySize (sbatch
// would refuse every full array), or a prologue that cannot be read.
std::vector<std::string> write_slurm_scripts(const SweepPlan& plan, int job_count, const SlurmOptions& options);

}  // namespace physarum::cli
