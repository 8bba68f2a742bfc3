#include "tools/sweep/slurm_script.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"
#include "tools/sweep/sweep_pool.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;

std::string read_prologue(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw UsageError("--prologue " + path + ": cannot read the file");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  if (!s.empty() && s.back() != '\n') s += '\n';
  return s;
}

// One array: tasks 0..count-1 run jobs first..first+count-1.
//
// The folder may have moved since the script was written, so the script names no place Slurm must
// open before it starts: --output is /dev/null (slurmd opens it before the script runs, and a task
// whose output file cannot be opened dies unseen), the script finds its folder (its own, or under
// Slurm, which runs a copy from its spool, the submitted script's, which scontrol names) and only
// then sends its output into DIR/logs. The folder it was written in is the fallback.
std::string array_script(const SweepPlan& plan, const fs::path& script, int first, int count, int job_count,
                         const SlurmOptions& options, const std::string& prologue) {
  std::string s = "#!/bin/bash\n";
  s += "# physarum sweep: jobs " + std::to_string(first) + ".." + std::to_string(first + count - 1) + " of " +
       std::to_string(job_count) + " runs of " + plan.inputs.scene + " as a Slurm array job. Task i runs\n";
  s += "# job " + std::to_string(first) + " + i (line " + std::to_string(first) + " + i, 0-based, of jobs.jsonl) in the "
       "folder this script is in;\n";
  s += "# a finished run is skipped and a stopped one resumes from its checkpoint, so submitting again\n";
  s += "# continues. The folder may be moved or copied first. Submit with\n#   sbatch " +
       script.filename().string() + "   (from the sweep folder, or give its path)\n";
  s += "# and gather the results with: physarum sweep --collect DIR. Logs: DIR/logs/.\n";
  s += "#SBATCH --job-name=physarum-sweep\n";
  s += "#SBATCH --array=0-" + std::to_string(count - 1) + "\n";
  s += "#SBATCH --ntasks=1\n";
  s += "#SBATCH --cpus-per-task=1\n";
  if (options.gpu) s += "#SBATCH --gres=gpu:1\n";
  for (const std::string& line : options.sbatch) s += "#SBATCH " + line + "\n";
  s += "#SBATCH --output=/dev/null\n";
  s += "set -euo pipefail\n";
  s += "task=\"${SLURM_ARRAY_TASK_ID:?is not set: submit with sbatch, or set it by hand to run one task}\"\n";
  s += "# The sweep folder is the one holding this script. Slurm runs a copy from its spool, so there it\n";
  s += "# is the folder of the script that was submitted, which scontrol names.\n";
  s += "script=${BASH_SOURCE[0]}\n";
  s += "if [[ -n ${SLURM_JOB_ID:-} ]]; then\n";
  s += "  script=$(scontrol show job \"${SLURM_ARRAY_JOB_ID:-$SLURM_JOB_ID}_$task\" 2>/dev/null | sed -n 's/^ *Command=//p' | head -n 1) || true\n";
  s += "  if [[ -n $script && $script != /* ]]; then script=\"${SLURM_SUBMIT_DIR:-.}/$script\"; fi\n";
  s += "fi\n";
  s += "folder=$(dirname \"$script\")\n";
  s += "if [[ ! -f $folder/sweep.json ]]; then folder=" + shell_command({plan.folder}) + "; fi  # where it was written\n";
  s += "if [[ -n ${SLURM_JOB_ID:-} ]]; then\n";
  s += "  log=\"$folder/logs/slurm-${SLURM_ARRAY_JOB_ID:-$SLURM_JOB_ID}_$task.out\"\n";
  s += "  if ! { mkdir -p \"$folder/logs\" && exec >>\"$log\" 2>&1; }; then\n";
  s += "    echo \"physarum sweep: no sweep folder to run in ($folder is not writable or gone)\" \\\n";
  s += "      >\"${SLURM_SUBMIT_DIR:-.}/physarum-sweep-${SLURM_JOB_ID}.err\"\n";
  s += "    exit 1\n";
  s += "  fi\n";
  s += "fi\n";
  if (!prologue.empty()) s += "# ---- the site's prologue (--prologue) ----\n" + prologue + "# ----\n";
  s += "# The program that planned the sweep, else the one on the PATH (a folder planned elsewhere).\n";
  s += "physarum=" + shell_command({this_executable()}) + "\n";
  s += "[[ -x $physarum ]] || physarum=$(command -v physarum) || { echo \"physarum sweep: no physarum program here\" >&2; exit 1; }\n";
  s += "exec \"$physarum\" sweep \"$folder\" --job \"$((" + std::to_string(first) + " + task))\"\n";
  return s;
}

}  // namespace

std::optional<int> site_max_array_size() {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen("scontrol show config 2>/dev/null", "r"), ::pclose);
  if (!pipe) return std::nullopt;
  std::string text;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0;) text.append(buffer, n);
  std::smatch m;
  static const std::regex line(R"(MaxArraySize\s*=\s*(\d+))");
  if (std::regex_search(text, m, line)) return std::max(1, std::stoi(m[1].str()));
  return std::nullopt;
}

std::vector<std::string> write_slurm_scripts(const SweepPlan& plan, int job_count, const SlurmOptions& options) {
  const std::optional<int> site = site_max_array_size();
  const int max_array = options.max_array.value_or(site.value_or(kSlurmDefaultMaxArraySize));
  if (max_array < 1) throw UsageError("--max-array " + std::to_string(max_array) + " must be >= 1");
  if (site && max_array > *site)
    throw UsageError("--max-array " + std::to_string(max_array) + " is past this site's MaxArraySize " +
                     std::to_string(*site) + " (scontrol show config): sbatch would refuse the arrays; leave it out to use the site's");
  const std::string prologue = options.prologue.empty() ? std::string() : read_prologue(options.prologue);
  const int parts = (job_count + max_array - 1) / max_array;
  std::vector<std::string> scripts;
  for (int k = 0; k < parts; ++k) {
    const fs::path script =
        fs::path(plan.folder) / (parts == 1 ? std::string("sweep.slurm") : "sweep_" + std::to_string(k) + ".slurm");
    const int first = k * max_array, count = std::min(max_array, job_count - first);
    write_text_file_atomically(script.string(), array_script(plan, script, first, count, job_count, options, prologue));
    fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
    scripts.push_back(script.string());
  }
  return scripts;
}

}  // namespace physarum::cli
