// `physarum sweep` as a user runs it: a 3 x 2 grid x 2 seeds plans 12 jobs with the right values,
// --run runs each exactly once (a second --run skips them all), the Slurm script is valid bash and
// runs its task 0 when SLURM_ARRAY_TASK_ID=0 is set by hand, GNU parallel's file holds one job per
// line (`physarum sweep DIR --job I`), a job stopped after a checkpoint resumes from it to the
// uninterrupted run's bytes, a failing job is reported without stopping the others, and --collect
// gives one CSV row per job and a contact sheet of the grid's size.
#include "killed_run.hpp"
#include "test_support.hpp"
#include "tiny_sweep_scene.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;

const char* kScene = kTinySweepScene;
const char* kRunOptions = kTinySweepRunOptions;

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) lines.push_back(line);
  return lines;
}

class SweepCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    std::ofstream(dir_->path / "scene.json") << kScene;
    plan_ = run_physarum("sweep " + quoted(dir_->path / "scene.json") +
                         " --vary turn_rate=90,180,360 --vary sensor_angle=22.5,45 --seeds 2" + kRunOptions +
                         " --out " + quoted(sweep()) + " --emit slurm --emit parallel");
    first_ = run_physarum("sweep " + quoted(sweep()) + " --run --jobs 2");
    for (int i = 0; i < 12; ++i) mtimes_.push_back(fs::last_write_time(run_json(i)));
    second_ = run_physarum("sweep " + quoted(sweep()) + " --run --jobs 2");
  }
  static void TearDownTestSuite() { delete dir_; }
  static fs::path sweep() { return dir_->path / "sweep"; }
  static fs::path run_json(int i) {
    char name[32];
    std::snprintf(name, sizeof name, "run_%04d", i);
    return sweep() / name / "run.json";
  }
  static inline TempDir* dir_ = nullptr;
  static inline CommandResult plan_, first_, second_;
  static inline std::vector<fs::file_time_type> mtimes_;
};

TEST_F(SweepCommand, PlansTwelveJobsWithTheRightValues) {
  ASSERT_EQ(plan_.exit_code, 0) << plan_.err;
  const std::vector<std::string> lines = lines_of(sweep() / "jobs.jsonl");
  ASSERT_EQ(lines.size(), 12u);
  // The grid spelled out independently: the first key slowest, the seeds (3, 4: the scene's seed on)
  // innermost.
  int i = 0;
  std::set<std::string> outs;
  for (const double turn_rate : {90.0, 180.0, 360.0})
    for (const double sensor_angle : {22.5, 45.0})
      for (const int seed : {3, 4}) {
        const auto j = nlohmann::json::parse(lines[static_cast<size_t>(i)]);
        EXPECT_EQ(j["index"], i);
        EXPECT_EQ(j["overrides"]["turn_rate"].get<double>(), turn_rate) << lines[static_cast<size_t>(i)];
        EXPECT_EQ(j["overrides"]["sensor_angle"].get<double>(), sensor_angle) << lines[static_cast<size_t>(i)];
        EXPECT_EQ(j["overrides"].size(), 2u);
        EXPECT_EQ(j["seed"], seed);
        outs.insert(j["out"].get<std::string>());
        const auto args = j["args"].get<std::vector<std::string>>();
        EXPECT_EQ(args.front(), "run");
        EXPECT_NE(std::find(args.begin(), args.end(), "--seed"), args.end());
        ++i;
      }
  EXPECT_EQ(outs.size(), 12u) << "every job has its own output folder";
}

TEST_F(SweepCommand, RunTwiceRunsEachJobOnce) {
  ASSERT_EQ(first_.exit_code, 0) << first_.err;
  EXPECT_NE(first_.out.find("ran 12, skipped 0"), std::string::npos) << first_.out;
  ASSERT_EQ(second_.exit_code, 0) << second_.err;
  EXPECT_NE(second_.out.find("ran 0, skipped 12"), std::string::npos) << second_.out;
  for (int i = 0; i < 12; ++i) EXPECT_EQ(fs::last_write_time(run_json(i)), mtimes_[static_cast<size_t>(i)]) << "job " << i;
  // Each run simulated its own variant and seed: job 9 is turn_rate 360, sensor_angle 22.5, seed 4.
  std::ifstream in(run_json(9));
  const auto j = nlohmann::json::parse(in);
  EXPECT_NEAR(j["parameters"]["turn_rate"].get<double>(), 360.0, 1e-9) << j["parameters"].dump();
  EXPECT_NEAR(j["parameters"]["sensor_angle"].get<double>(), 22.5, 1e-9) << j["parameters"].dump();
  EXPECT_EQ(j["parameters"]["seed"], 4);
}

TEST_F(SweepCommand, SlurmScriptIsValidAndRunsItsTaskZero) {
  const fs::path script = sweep() / "sweep.slurm";
  ASSERT_TRUE(fs::exists(script));
  EXPECT_EQ(shell("bash -n " + quoted(script)), 0);
  std::stringstream text;
  text << std::ifstream(script).rdbuf();
  EXPECT_NE(text.str().find("#SBATCH --array=0-11\n"), std::string::npos) << text.str();

  // A fresh sweep of the same grid, so task 0 has something to do.
  const fs::path fresh = dir_->path / "slurm";
  ASSERT_EQ(run_physarum("sweep " + quoted(dir_->path / "scene.json") +
                         " --vary turn_rate=90,180,360 --vary sensor_angle=22.5,45 --seeds 2" + kRunOptions + " --out " +
                         quoted(fresh) + " --emit slurm")
                .exit_code,
            0);
  EXPECT_EQ(shell("SLURM_ARRAY_TASK_ID=0 bash " + quoted(fresh / "sweep.slurm") + " >/dev/null 2>&1"), 0);
  EXPECT_TRUE(fs::exists(fresh / "run_0000" / "run.json"));
  EXPECT_FALSE(fs::exists(fresh / "run_0001"));
  // Without the variable the script refuses instead of guessing a task.
  EXPECT_NE(shell("env -u SLURM_ARRAY_TASK_ID bash " + quoted(fresh / "sweep.slurm") + " >/dev/null 2>&1"), 0);
}

TEST_F(SweepCommand, ParallelFileHoldsOneJobPerLineThatSkipsAFinishedRun) {
  const std::vector<std::string> lines = lines_of(sweep() / "jobs.txt");
  ASSERT_EQ(lines.size(), 12u);
  for (size_t i = 0; i < lines.size(); ++i)
    EXPECT_NE(lines[i].find(" sweep "), std::string::npos) << lines[i];
  EXPECT_EQ(lines[5].substr(lines[5].size() - 8), " --job 5") << lines[5];
  // Line 5 run by hand in the folder (as GNU parallel would) after the sweep ran: the finished run is
  // skipped.
  EXPECT_EQ(shell("cd " + quoted(sweep()) + " && " + lines[5] + " > " + quoted(dir_->path / "line5.txt") + " 2>&1"), 0)
      << lines[5];
  std::stringstream said;
  said << std::ifstream(dir_->path / "line5.txt").rdbuf();
  EXPECT_NE(said.str().find("job 5 finished before"), std::string::npos) << said.str();
}

TEST_F(SweepCommand, CollectGivesARowPerJobAndASheetOfTheGridsSize) {
  const CommandResult r = run_physarum("sweep --collect " + quoted(sweep()) + " --thumbnail 40");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> rows = lines_of(sweep() / "sweep.csv");
  ASSERT_EQ(rows.size(), 13u);  // header + 12 runs
  EXPECT_EQ(rows[0].rfind("index,turn_rate,sensor_angle,seed,out,status,", 0), 0u) << rows[0];
  EXPECT_NE(rows[0].find(",final_mean"), std::string::npos) << rows[0];
  EXPECT_NE(rows[0].find(",agent_steps_per_second"), std::string::npos) << rows[0];
  EXPECT_EQ(rows[10].rfind("9,360,22.5,4,", 0), 0u) << rows[10];
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_NE(rows[i].find(",done,"), std::string::npos) << rows[i];

  // 3 rows (turn_rate) x 2 columns (sensor_angle), 2 seeds per cell, 40 px thumbnails, 8 px gaps,
  // a 48 px header, and row labels as wide as "turn_rate=360" (13 characters at 9 px + 16 px).
  auto in = OIIO::ImageInput::open((sweep() / "contact_sheet.png").string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, (13 * 9 + 16) + 2 * (2 * 40 + 8) + 8);
  EXPECT_EQ(in->spec().height, 48 + 3 * (40 + 8) + 8);
}

// A run measured with `physarum analyze` adds its analysis.json's scalars (nested keys joined by '_',
// lists left out) as analysis_ columns; the runs not measured leave them empty.
TEST_F(SweepCommand, CollectTakesTheScalarsOfEachRunsAnalysis) {
  const fs::path analysis = run_json(0).parent_path() / "analysis.json";
  std::ofstream(analysis) << R"({"spot_count": 7, "spots": [{"area": 1.0}], "summary": {"interior_spot_area": {"median": 0.25, "max": null}}})";
  const CommandResult r = run_physarum("sweep --collect " + quoted(sweep()) + " --thumbnail 20");
  fs::remove(analysis);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> rows = lines_of(sweep() / "sweep.csv");
  ASSERT_EQ(rows.size(), 13u);
  EXPECT_EQ(rows[0].find(",analysis_spots"), std::string::npos) << rows[0];
  const std::string columns = ",analysis_spot_count,analysis_summary_interior_spot_area_median,analysis_summary_interior_spot_area_max";
  ASSERT_GE(rows[0].size(), columns.size());
  EXPECT_EQ(rows[0].substr(rows[0].size() - columns.size()), columns) << rows[0];
  EXPECT_EQ(rows[1].substr(rows[1].size() - 8), ",7,0.25,") << rows[1];
  EXPECT_EQ(rows[2].substr(rows[2].size() - 3), ",,,") << rows[2];
}

// 2,500 jobs with --max-array 1000: three arrays (1000, 1000, 500 tasks) whose tasks, offset by
// their part, name every job exactly once; each script is valid bash, and part 2's task 0 runs job
// 2000. The site options land in every script: #SBATCH lines, the GPU request, the prologue before
// the job.
TEST(SweepSlurm, ArraysPastTheLimitAreSplitAndCoverEveryJobOnce) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << kScene;
  // What a site's prologue does (a real one would `module load`, which this machine has not).
  std::ofstream(dir.path / "prologue.sh") << "export OMP_NUM_THREADS=1\necho \"prologue ran\"\n";
  std::string agents;
  for (int a = 100; a < 150; ++a) {
    if (a > 100) agents += ',';
    agents += std::to_string(a);
  }
  const CommandResult plan = run_physarum(
      "sweep " + quoted(dir.path / "scene.json") + " --vary agents=" + agents + " --seeds 50" + kRunOptions + " --out " +
      quoted(dir.path / "s") + " --emit slurm --max-array 1000 --sbatch --time=00:10:00 --sbatch --mem=1G --gpu" +
      " --prologue " + quoted(dir.path / "prologue.sh"));
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  EXPECT_FALSE(fs::exists(dir.path / "s" / "sweep.slurm")) << "more jobs than one array takes: parts only";
  std::vector<int> covered(2500, 0);
  const std::regex array(R"re(#SBATCH --array=0-(\d+)\n)re"), job(R"re("\$\(\((\d+) \+ task\)\)")re");
  for (int part = 0; part < 3; ++part) {
    const fs::path script = dir.path / "s" / ("sweep_" + std::to_string(part) + ".slurm");
    ASSERT_TRUE(fs::exists(script)) << script;
    EXPECT_EQ(shell("bash -n " + quoted(script)), 0) << script;
    std::stringstream text;
    text << std::ifstream(script).rdbuf();
    const std::string s = text.str();
    std::smatch a, j;
    ASSERT_TRUE(std::regex_search(s, a, array)) << s;
    ASSERT_TRUE(std::regex_search(s, j, job)) << s;
    const int last_task = std::stoi(a[1].str()), first_job = std::stoi(j[1].str());
    EXPECT_LE(last_task, 999) << "array indices stay under --max-array";
    for (int task = 0; task <= last_task; ++task) ++covered.at(static_cast<size_t>(first_job + task));
    for (const char* line : {"#SBATCH --time=00:10:00\n", "#SBATCH --mem=1G\n", "#SBATCH --gres=gpu:1\n"})
      EXPECT_NE(s.find(line), std::string::npos) << line << " missing from " << script;
    const size_t prologue = s.find("export OMP_NUM_THREADS=1\necho \"prologue ran\"\n");
    ASSERT_NE(prologue, std::string::npos) << s;
    EXPECT_LT(prologue, s.find("exec \"$physarum\"")) << "the prologue runs before the job";
  }
  EXPECT_FALSE(fs::exists(dir.path / "s" / "sweep_3.slurm"));
  EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), 2500) << "every job in exactly one array task";
  EXPECT_EQ(shell("SLURM_ARRAY_TASK_ID=0 bash " + quoted(dir.path / "s" / "sweep_2.slurm") + " > " +
                  quoted(dir.path / "task.txt") + " 2>&1"),
            0);
  std::stringstream task;
  task << std::ifstream(dir.path / "task.txt").rdbuf();
  EXPECT_EQ(task.str().rfind("prologue ran\n", 0), 0u) << task.str();
  EXPECT_TRUE(fs::exists(dir.path / "s" / "run_2000" / "run.json"));
  EXPECT_FALSE(fs::exists(dir.path / "s" / "run_0000"));
}

TEST(SweepSlurm, SiteOptionsWithoutSlurmAreAUsageError) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << kScene;
  const CommandResult r = run_physarum("sweep " + quoted(dir.path / "scene.json") + " --vary agents=100,200" +
                                       kRunOptions + " --out " + quoted(dir.path / "s") + " --max-array 5");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("give them with --emit slurm"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "s"));
}

// A job stopped the hard way after its first checkpoint (as a preempted or cancelled Slurm task is)
// continues from that checkpoint when it is run again, through --job as through --run, and ends with
// the bytes of the same job run without a stop.
TEST(SweepResume, AStoppedJobResumesFromItsCheckpointToTheUninterruptedBytes) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << kScene;
  auto plan = [&](const std::string& name) {
    return run_physarum("sweep " + quoted(dir.path / "scene.json") + " --vary agents=300,400 --steps 1500 "
                        "--backend reference --texture-size 16 --checkpoint-every 0.05 --out " + quoted(dir.path / name));
  };
  ASSERT_EQ(plan("straight").exit_code, 0);
  ASSERT_EQ(plan("stopped").exit_code, 0);
  ASSERT_EQ(run_physarum("sweep " + quoted(dir.path / "straight") + " --run --jobs 2").exit_code, 0);
  for (const int job : {0, 1}) {
    const fs::path out = dir.path / "stopped" / ("run_000" + std::to_string(job));
    ASSERT_TRUE(run_and_kill({"sweep", (dir.path / "stopped").string(), "--job", std::to_string(job)},
                             out / "checkpoint.bin", 11 + static_cast<unsigned>(job)))
        << "job " << job << " finished before it could be stopped: make the runs longer";
    ASSERT_FALSE(fs::exists(out / "run.json"));
    ASSERT_TRUE(fs::exists(out / "checkpoint.bin"));
  }
  // Moved after the stop (the checkpoints name the old place), as a requeued task may find it.
  fs::rename(dir.path / "stopped", dir.path / "moved");
  const CommandResult by_job = run_physarum("sweep " + quoted(dir.path / "moved") + " --job 0");
  EXPECT_EQ(by_job.exit_code, 0) << by_job.err;
  EXPECT_NE(by_job.out.find("job 0 resumes from its checkpoint"), std::string::npos) << by_job.out;
  const std::string log = bytes_of(dir.path / "moved" / "logs" / "run_0000.log");
  EXPECT_NE(log.find("resuming"), std::string::npos) << log;
  EXPECT_EQ(run_physarum("sweep " + quoted(dir.path / "moved") + " --run --jobs 1").exit_code, 0);
  for (const char* run : {"run_0000", "run_0001"})
    for (const char* file : {"pheromone.ply", "stats.csv"})
      EXPECT_EQ(bytes_of(dir.path / "moved" / run / file), bytes_of(dir.path / "straight" / run / file))
          << run << "/" << file << " differs from the uninterrupted run's";
  EXPECT_FALSE(fs::exists(dir.path / "stopped")) << "nothing was written to the old place";
}

// A partial sweep is still collected (rows and grey cells for what is not done), and the command
// fails, naming the jobs that never ran and those that started and did not finish.
TEST(SweepFailures, CollectOfAPartialSweepWritesItAndExitsOneListingWhatIsMissing) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << kScene;
  ASSERT_EQ(run_physarum("sweep " + quoted(dir.path / "scene.json") + " --vary agents=100,200,300" + kRunOptions +
                         " --out " + quoted(dir.path / "s"))
                .exit_code,
            0);
  ASSERT_EQ(run_physarum("sweep " + quoted(dir.path / "s") + " --job 0").exit_code, 0);
  fs::create_directories(dir.path / "s" / "run_0002");  // started, stopped before run.json
  const CommandResult r = run_physarum("sweep --collect " + quoted(dir.path / "s") + " --thumbnail 20");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("failed or unfinished jobs (folder without run.json; logs in "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/logs/): 2\n"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("jobs never run: 1\n"), std::string::npos) << r.err;
  const std::vector<std::string> rows = lines_of(dir.path / "s" / "sweep.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_NE(rows[1].find(",done,"), std::string::npos) << rows[1];
  EXPECT_NE(rows[2].find(",missing"), std::string::npos) << rows[2];
  EXPECT_NE(rows[3].find(",failed"), std::string::npos) << rows[3];
}

TEST(SweepFailures, ABadVariantIsRefusedBeforeAnyJobExists) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << kScene;
  const CommandResult r = run_physarum("sweep " + quoted(dir.path / "scene.json") + " --vary agents=100,-5" + kRunOptions +
                                       " --out " + quoted(dir.path / "s"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("variant 1 {\"agents\":-5}"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "s" / "jobs.jsonl"));
}

// A job that fails only when it runs (far more agents than memory holds: refused by the run).
TEST(SweepFailures, AFailedJobIsReportedAndTheOthersStillRun) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << kScene;
  const CommandResult r = run_physarum("sweep " + quoted(dir.path / "scene.json") + " --vary agents=2000000000,100" + kRunOptions +
                                       " --out " + quoted(dir.path / "s") + " --run --jobs 2");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("job 0 (run_0000) failed (exit code 1)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "s" / "run_0000" / "run.json"));
  EXPECT_TRUE(fs::exists(dir.path / "s" / "run_0001" / "run.json"));
}

TEST(SweepFailures, AnotherSweepIntoTheSameFolderIsRefused) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << kScene;
  const std::string plan = "sweep " + quoted(dir.path / "scene.json") + kRunOptions + " --out " + quoted(dir.path / "s");
  ASSERT_EQ(run_physarum(plan + " --vary turn_rate=90,180").exit_code, 0);
  EXPECT_EQ(run_physarum(plan + " --vary turn_rate=90,180").exit_code, 0);  // the same sweep: kept
  const CommandResult other = run_physarum(plan + " --vary turn_rate=45");
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_NE(other.err.find("already holds another sweep"), std::string::npos) << other.err;
}

}  // namespace
}  // namespace physarum::testing
