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
std::string array_script(const SweepPlan& plan, const fs::path& script, int first, int count, int job_count,
                         const SlurmOptions& options, const std::string& prologue) {
  const fs::path dir(plan.folder);
  std::string s = "#!/bin/bash\n";
  s += "# physarum sweep: jobs " + std::to_string(first) + ".." + std::to_string(first + count - 1) + " of " +
       std::to_string(job_count) + " runs of " + plan.scene + "\n";
  s += "# as a Slurm array job. Task i runs job " + std::to_string(first) + " + i (line " + std::to_string(first) +
       " + i, 0-based, of " + (dir / "jobs.jsonl").string() + ");\n";
  s += "# a finished run is skipped and a stopped one resumes from its checkpoint, so submitting again\n";
  s += "# continues. Submit with\n#   sbatch " + script.string() + "\n";
  s += "# and gather the results with: physarum sweep --collect " + plan.folder + "\n";
  s += "#SBATCH --job-name=physarum-sweep\n";
  s += "#SBATCH --array=0-" + std::to_string(count - 1) + "\n";
  s += "#SBATCH --ntasks=1\n";
  s += "#SBATCH --cpus-per-task=1\n";
  if (options.gpu) s += "#SBATCH --gres=gpu:1\n";
  for (const std::string& line : options.sbatch) s += "#SBATCH " + line + "\n";
  s += "#SBATCH --output=" + (dir / "logs" / "slurm-%A_%a.out").string() + "\n";
  s += "set -euo pipefail\n";
  s += "task=\"${SLURM_ARRAY_TASK_ID:?is not set: submit with sbatch, or set it by hand to run one task}\"\n";
  if (!prologue.empty()) s += "# ---- the site's prologue (--prologue) ----\n" + prologue + "# ----\n";
  s += "exec " + shell_command({this_executable(), "sweep", plan.folder, "--job"}) + " \"$((" + std::to_string(first) +
       " + task))\"\n";
  return s;
}

}  // namespace

int site_max_array_size() {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen("scontrol show config 2>/dev/null", "r"), ::pclose);
  if (!pipe) return kSlurmDefaultMaxArraySize;
  std::string text;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0;) text.append(buffer, n);
  std::smatch m;
  static const std::regex line(R"(MaxArraySize\s*=\s*(\d+))");
  if (std::regex_search(text, m, line)) return std::max(1, std::stoi(m[1].str()));
  return kSlurmDefaultMaxArraySize;
}

std::vector<std::string> write_slurm_scripts(const SweepPlan& plan, int job_count, const SlurmOptions& options) {
  const int max_array = options.max_array ? *options.max_array : site_max_array_size();
  if (max_array < 1) throw UsageError("--max-array " + std::to_string(max_array) + " must be >= 1");
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
