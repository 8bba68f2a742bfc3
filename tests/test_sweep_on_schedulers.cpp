// Sweeps through the real schedulers, as a cluster user runs them. A private single-node Slurm 22.05
// (tests/slurm/private_slurm.sh: munge, slurmctld and slurmd started by the suite as root in a
// folder of their own, stopped by it) takes a sweep folder moved after planning: every array task
// runs in the new place and a resubmission skips them all; a task cancelled after its first
// checkpoint resumes on resubmission to the bytes of an uninterrupted run; arrays split at
// --max-array, or at the site's MaxArraySize read from scontrol, are accepted by sbatch and one past
// the limit is not. GNU parallel runs the same kind of folder from its jobs.txt. Where the daemons
// cannot start (not root, Debian's slurm-wlm/munge/parallel absent: tools/setup.sh --tests installs
// them) the tests skip and say why.
#include "killed_run.hpp"
#include "test_support.hpp"
#include "tiny_sweep_scene.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const char* kScene = kTinySweepScene;
const char* kRunOptions = kTinySweepRunOptions;
// The private site's array limit, not Slurm's default (1001), so that reading it from scontrol shows.
constexpr int kSiteMaxArraySize = 1200;

fs::path slurm_script() { return fs::path(PHYSARUM_SOURCE_DIR) / "tests" / "slurm" / "private_slurm.sh"; }

std::vector<fs::file_time_type> run_json_times(const fs::path& sweep, int jobs) {
  std::vector<fs::file_time_type> times;
  for (int i = 0; i < jobs; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "run_%04d", i);
    times.push_back(fs::exists(sweep / name / "run.json") ? fs::last_write_time(sweep / name / "run.json")
                                                          : fs::file_time_type::min());
  }
  return times;
}

// Polls `done` every 100 ms for at most `limit`.
template <class F>
bool wait_until(F done, std::chrono::seconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(100ms);
  }
  return true;
}

class SweepOnSlurm : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    state_ = new TempDir;
    const CommandResult r = run_command("PRIVATE_SLURM_MAX_ARRAY=" + std::to_string(kSiteMaxArraySize) + " bash " +
                                        quoted(slurm_script()) + " start " + quoted(state_->path / "slurm"));
    if (r.exit_code == 77) {
      skip_ = r.err;
    } else if (r.exit_code != 0) {
      failure_ = "private_slurm.sh start exited " + std::to_string(r.exit_code) + ": " + r.out + r.err;
    } else {
      started_ = true;
      ::setenv("SLURM_CONF", (state_->path / "slurm" / "slurm.conf").c_str(), 1);
    }
  }
  static void TearDownTestSuite() {
    if (started_) shell("bash " + quoted(slurm_script()) + " stop " + quoted(state_->path / "slurm") + " >/dev/null 2>&1");
    ::unsetenv("SLURM_CONF");
    delete state_;
  }
  void SetUp() override {
    if (!skip_.empty()) GTEST_SKIP() << skip_;
    ASSERT_TRUE(failure_.empty()) << failure_;
  }
  // Plans a sweep of the tiny scene into `out` (extra: more options).
  static void plan(const fs::path& out, const std::string& vary, const std::string& extra) {
    std::ofstream(out.parent_path() / "scene.json") << kScene;
    const CommandResult r = run_physarum("sweep " + quoted(out.parent_path() / "scene.json") + " --vary " + vary + " " +
                                         extra + " --out " + quoted(out) + " --emit slurm");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  // `sbatch --wait` from `folder` (so a relative script path is what Slurm records), at most 3 min.
  static CommandResult submit_and_wait(const fs::path& folder, const std::string& script) {
    return run_command("cd " + quoted(folder) + " && timeout 180 sbatch --wait " + quoted(fs::path(script)));
  }
  static inline TempDir* state_ = nullptr;
  static inline std::string skip_, failure_;
  static inline bool started_ = false;
};

TEST_F(SweepOnSlurm, AMovedSweepRunsEveryTaskWhereItIsAndAResubmissionSkipsThem) {
  TempDir dir;
  fs::create_directories(dir.path / "laptop");
  plan(dir.path / "laptop" / "sweep", "turn_rate=90,180", std::string("--seeds 2") + kRunOptions);
  fs::create_directories(dir.path / "scratch");
  fs::rename(dir.path / "laptop", dir.path / "scratch" / "laptop");  // the folder moves after planning
  const fs::path sweep = dir.path / "scratch" / "laptop" / "sweep";

  const CommandResult first = submit_and_wait(dir.path / "scratch", "laptop/sweep/sweep.slurm");
  ASSERT_EQ(first.exit_code, 0) << first.out << first.err;
  const std::vector<fs::file_time_type> finished = run_json_times(sweep, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NE(finished[static_cast<size_t>(i)], fs::file_time_type::min()) << "job " << i;
  EXPECT_FALSE(fs::exists(dir.path / "laptop")) << "a task wrote to the folder's old place";
  int task_logs = 0;
  for (const auto& entry : fs::directory_iterator(sweep / "logs"))
    task_logs += entry.path().filename().string().rfind("slurm-", 0) == 0;
  EXPECT_EQ(task_logs, 4) << "each task's lines in the folder's logs/";
  const CommandResult collect = run_physarum("sweep --collect " + quoted(sweep) + " --thumbnail 16");
  EXPECT_EQ(collect.exit_code, 0) << collect.err;

  const CommandResult again = submit_and_wait(sweep, "sweep.slurm");
  ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_EQ(run_json_times(sweep, 4), finished) << "a resubmission ran a finished job again";
}

TEST_F(SweepOnSlurm, ACancelledTaskResumesFromItsCheckpointToTheUninterruptedBytes) {
  TempDir dir;
  const std::string options = "--steps 30000 --backend reference --texture-size 16 --checkpoint-every 0.5";  // ~5 s
  plan(dir.path / "straight", "agents=300", options);
  plan(dir.path / "cancelled", "agents=300", options);
  ASSERT_EQ(run_physarum("sweep " + quoted(dir.path / "straight") + " --run --jobs 1").exit_code, 0);

  const CommandResult submitted = run_command("sbatch --parsable " + quoted(dir.path / "cancelled" / "sweep.slurm"));
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  const std::string job = submitted.out.substr(0, submitted.out.find_first_of(";\n"));  // JOBID[;CLUSTER]
  const fs::path out = dir.path / "cancelled" / "run_0000";
  ASSERT_TRUE(wait_until([&] { return fs::exists(out / "checkpoint.bin") || fs::exists(out / "run.json"); }, 120s))
      << "the task never wrote a checkpoint";
  ASSERT_EQ(shell("scancel " + job), 0);
  ASSERT_TRUE(wait_until([&] { return run_command("squeue -h -j " + job).out.empty(); }, 60s)) << "scancel left job " << job;
  ASSERT_FALSE(fs::exists(out / "run.json")) << "the run finished before it was cancelled: make it longer";
  ASSERT_TRUE(fs::exists(out / "checkpoint.bin"));

  const CommandResult resubmitted = submit_and_wait(dir.path / "cancelled", "sweep.slurm");
  ASSERT_EQ(resubmitted.exit_code, 0) << resubmitted.out << resubmitted.err;
  EXPECT_NE(bytes_of(dir.path / "cancelled" / "logs" / "run_0000.log").find("resuming"), std::string::npos);
  for (const char* file : {"pheromone.ply", "stats.csv"})
    EXPECT_EQ(bytes_of(out / file), bytes_of(dir.path / "straight" / "run_0000" / file)) << file;
}

// 2,500 jobs: three arrays of at most 1,000 tasks at --max-array 1000, three of at most 1,200 at the
// site's limit (read from scontrol), every script accepted by `sbatch --test-only`; an array one past
// the site's limit is refused by sbatch, so the acceptance means something, and a --max-array past
// it by physarum.
TEST_F(SweepOnSlurm, ArraysSplitAtTheLimitAreAcceptedBySbatch) {
  TempDir dir;
  std::string agents;
  for (int a = 100; a < 150; ++a) agents.append(agents.empty() ? "" : ",").append(std::to_string(a));
  plan(dir.path / "given", "agents=" + agents, std::string("--seeds 50 --max-array 1000") + kRunOptions);
  plan(dir.path / "site", "agents=" + agents, std::string("--seeds 50") + kRunOptions);
  for (const auto& [folder, tasks] : {std::pair{"given", 1000}, std::pair{"site", kSiteMaxArraySize}}) {
    for (int k = 0; k < 3; ++k) {
      const fs::path script = dir.path / folder / ("sweep_" + std::to_string(k) + ".slurm");
      ASSERT_TRUE(fs::exists(script)) << script;
      const int last = k < 2 ? tasks - 1 : 2500 - 2 * tasks - 1;
      EXPECT_NE(bytes_of(script).find("#SBATCH --array=0-" + std::to_string(last) + "\n"), std::string::npos) << script;
      const CommandResult r = run_command("sbatch --test-only " + quoted(script));
      EXPECT_EQ(r.exit_code, 0) << script << ": " << r.err;
    }
    EXPECT_FALSE(fs::exists(dir.path / folder / "sweep_3.slurm"));
  }
  std::ofstream(dir.path / "past.sh") << "#!/bin/bash\n#SBATCH --array=0-" << kSiteMaxArraySize << "\ntrue\n";
  EXPECT_NE(shell("sbatch --test-only " + quoted(dir.path / "past.sh") + " >/dev/null 2>&1"), 0)
      << "the private site does not enforce its MaxArraySize";
  const CommandResult past = run_physarum("sweep " + quoted(dir.path / "site") + " --emit slurm --max-array 1500");
  EXPECT_EQ(past.exit_code, 2);
  EXPECT_NE(past.err.find("past this site's MaxArraySize 1200"), std::string::npos) << past.err;
}

TEST(SweepWithParallel, AMovedSweepRunsThroughGnuParallelAndARerunSkipsEveryJob) {
  if (shell("command -v parallel >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "GNU parallel is not installed (Debian package parallel; tools/setup.sh --tests installs it)";
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << kScene;
  ASSERT_EQ(run_physarum("sweep " + quoted(dir.path / "scene.json") + " --vary turn_rate=90,180 --seeds 2" + kRunOptions +
                         " --out " + quoted(dir.path / "planned") + " --emit parallel")
                .exit_code,
            0);
  fs::rename(dir.path / "planned", dir.path / "moved");
  const fs::path sweep = dir.path / "moved";
  const std::string parallel = "cd " + quoted(sweep) + " && parallel --will-cite --halt now,fail=1 --jobs 2 < jobs.txt";
  const CommandResult first = run_command(parallel);
  ASSERT_EQ(first.exit_code, 0) << first.out << first.err;
  const std::vector<fs::file_time_type> finished = run_json_times(sweep, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NE(finished[static_cast<size_t>(i)], fs::file_time_type::min()) << "job " << i;
  EXPECT_FALSE(fs::exists(dir.path / "planned"));
  EXPECT_EQ(run_physarum("sweep --collect " + quoted(sweep) + " --thumbnail 16").exit_code, 0);
  const CommandResult again = run_command(parallel);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(run_json_times(sweep, 4), finished) << "a second pass ran a finished job again";
  EXPECT_NE(again.out.find("finished before"), std::string::npos) << again.out;
}

}  // namespace
}  // namespace physarum::testing
