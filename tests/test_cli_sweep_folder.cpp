// A sweep folder is self-contained (tools/sweep/frozen_inputs.hpp): planned in one place, moved or
// copied, it runs where it is now, through --run, a Slurm script run by hand and a GNU parallel line,
// and its runs give the bytes of the same runs made straight from the original files; an input
// changed after planning (the scene, the mesh, a colour map, an image a map reads) is refused,
// naming the file.
#include "killed_run.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;

// A scene that reads two files beside it (a mesh in a subfolder and, through the --vary, one of two
// colour-map files), so freezing has to copy them and rename the references.
const char* kOctahedron =
    "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
    "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
const char* kScene = R"({
  "mesh": "meshes/octahedron.obj", "scale_to_area": 1.0, "max_circumradius": 0.1, "agents": 200,
  "time_step": 0.01, "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5,
  "turn_rate": 180.0, "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0,
  "diffuse_rate": 0.0002, "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward",
  "seed": 3, "colormap": "warm.json"
})";
const char* kRunOptions = " --steps 4 --backend reference --texture-size 16";

class SweepFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_.path / "scenes" / "meshes");
    std::ofstream(dir_.path / "scenes" / "meshes" / "octahedron.obj") << kOctahedron;
    std::ofstream(dir_.path / "scenes" / "scene.json") << kScene;
    std::ofstream(dir_.path / "scenes" / "warm.json") << R"({"stops": [[0, "#200000"], [1, "#ffd040"]]})";
    std::ofstream(dir_.path / "scenes" / "cold.json") << R"({"stops": [[0, "#000020"], [1, "#40d0ff"]]})";
  }
  std::string plan_command(const fs::path& out) const {
    return "sweep " + quoted(dir_.path / "scenes" / "scene.json") + " --vary colormap=warm.json,cold.json" + kRunOptions +
           " --out " + quoted(out);
  }
  TempDir dir_;
};

TEST_F(SweepFolder, MovedOrCopiedItRunsWhereItIsWithTheOriginalFilesBytes) {
  const CommandResult plan = run_physarum(plan_command(dir_.path / "a") + " --emit slurm --emit parallel");
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  // Frozen: the scene, the mesh and both colour maps, named relative to the folder.
  for (const char* file : {"inputs/scene.json", "inputs/files/octahedron.obj", "inputs/files/warm.json", "inputs/files/cold.json"})
    EXPECT_TRUE(fs::exists(dir_.path / "a" / file)) << file;
  const std::string jobs = bytes_of(dir_.path / "a" / "jobs.jsonl") + bytes_of(dir_.path / "a" / "sweep.json") +
                           bytes_of(dir_.path / "a" / "jobs.txt");
  EXPECT_EQ(jobs.find((dir_.path / "a").string()), std::string::npos) << "the plan names the place it was planned in:\n" << jobs;

  fs::copy(dir_.path / "a", dir_.path / "c", fs::copy_options::recursive);
  fs::rename(dir_.path / "a", dir_.path / "b");
  // The original files gone too (planned on another machine): the folder needs nothing outside it.
  fs::rename(dir_.path / "scenes", dir_.path / "elsewhere");

  ASSERT_EQ(run_physarum("sweep " + quoted(dir_.path / "b") + " --run --jobs 2").exit_code, 0);
  for (const char* run : {"run_0000", "run_0001"}) EXPECT_TRUE(fs::exists(dir_.path / "b" / run / "run.json")) << run;
  EXPECT_FALSE(fs::exists(dir_.path / "a")) << "a moved sweep recreated its old folder";
  const CommandResult collect = run_physarum("sweep --collect " + quoted(dir_.path / "b") + " --thumbnail 16");
  EXPECT_EQ(collect.exit_code, 0) << collect.err;

  // The copy: its Slurm task 1 (run by hand) and its parallel line 0 write into the copy only.
  EXPECT_EQ(shell("SLURM_ARRAY_TASK_ID=1 bash " + quoted(dir_.path / "c" / "sweep.slurm") + " >/dev/null 2>&1"), 0);
  EXPECT_TRUE(fs::exists(dir_.path / "c" / "run_0001" / "run.json"));
  EXPECT_FALSE(fs::exists(dir_.path / "c" / "run_0000"));
  std::ifstream lines(dir_.path / "c" / "jobs.txt");
  std::string line0;
  std::getline(lines, line0);
  EXPECT_EQ(shell("cd " + quoted(dir_.path / "c") + " && " + line0 + " >/dev/null 2>&1"), 0) << line0;
  EXPECT_TRUE(fs::exists(dir_.path / "c" / "run_0000" / "run.json"));
  EXPECT_NE(bytes_of(dir_.path / "c" / "logs" / "run_0000.log").find("physarum run:"), std::string::npos)
      << "the run's output goes to the log inside the folder";

  // The same runs straight from the original files: the frozen copies changed nothing. The colour
  // map shows in the preview, the mesh in the pheromone values.
  for (const auto& [job, colormap] : {std::pair{"run_0000", "warm.json"}, std::pair{"run_0001", "cold.json"}}) {
    const fs::path direct = dir_.path / (std::string("direct_") + job);
    ASSERT_EQ(run_physarum("run " + quoted(dir_.path / "elsewhere" / "scene.json") + " --set colormap=" + colormap +
                           " --seed 3" + kRunOptions + " --out " + quoted(direct))
                  .exit_code,
              0);
    for (const char* file : {"pheromone.ply", "stats.csv", "preview.png"}) {
      EXPECT_EQ(bytes_of(dir_.path / "b" / job / file), bytes_of(direct / file)) << job << "/" << file;
      EXPECT_EQ(bytes_of(dir_.path / "c" / job / file), bytes_of(direct / file)) << job << "/" << file;
    }
  }
  EXPECT_NE(bytes_of(dir_.path / "b" / "run_0000" / "preview.png"), bytes_of(dir_.path / "b" / "run_0001" / "preview.png"))
      << "the two colour maps give the same preview: the --vary did not reach the runs";
}

TEST_F(SweepFolder, AnInputChangedAfterPlanningIsRefusedNamingIt) {
  const fs::path s = dir_.path / "s";
  ASSERT_EQ(run_physarum(plan_command(s)).exit_code, 0);
  const std::string scene = bytes_of(s / "inputs" / "scene.json");

  std::ofstream(s / "inputs" / "scene.json", std::ios::app) << " ";
  CommandResult r = run_physarum("sweep " + quoted(s) + " --job 0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("inputs/scene.json: changed since the sweep was planned"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(s / "run_0000"));
  std::ofstream(s / "inputs" / "scene.json", std::ios::trunc) << scene;  // restored: runs again
  EXPECT_EQ(run_physarum("sweep " + quoted(s) + " --job 0").exit_code, 0);

  std::ofstream(s / "inputs" / "files" / "cold.json", std::ios::trunc) << R"({"stops": [[0, "#000000"], [1, "#ffffff"]]})";
  r = run_physarum("sweep " + quoted(s) + " --run");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("inputs/files/cold.json: changed since the sweep was planned"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(s / "run_0001"));
  fs::remove(s / "inputs" / "files" / "octahedron.obj");
  r = run_physarum("sweep " + quoted(s) + " --job 1");
  EXPECT_NE(r.err.find("inputs/files/octahedron.obj: missing"), std::string::npos) << r.err;

  // The original edited and the same sweep planned again into the folder: refused, naming it.
  std::ofstream(dir_.path / "scenes" / "meshes" / "octahedron.obj", std::ios::app) << "# edited\n";
  r = run_physarum(plan_command(s));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("changed since it was planned there: " + (dir_.path / "scenes" / "meshes" / "octahedron.obj").string()),
            std::string::npos)
      << r.err;
}

// The shipped sign scene reads an image (sign/sign.png, two texture maps) and a vertex field: the
// image edited in the frozen folder after planning, a job refuses it by name before running.
TEST(SweepFolderImages, AnEditedImageAMapReadsIsRefusedNamingIt) {
  TempDir dir;
  const fs::path scene = fs::path(PHYSARUM_SOURCE_DIR) / "tools" / "scenes" / "sign.json";
  ASSERT_EQ(run_physarum("sweep " + quoted(scene) + " --vary agents=1000,2000" + kRunOptions + " --out " + quoted(dir.path / "s"))
                .exit_code,
            0);
  ASSERT_TRUE(fs::exists(dir.path / "s" / "inputs" / "files" / "sign.png"));
  EXPECT_EQ(bytes_of(dir.path / "s" / "inputs" / "files" / "sign.png"), bytes_of(scene.parent_path() / "sign" / "sign.png"));
  std::ofstream(dir.path / "s" / "inputs" / "files" / "sign.png", std::ios::app | std::ios::binary) << '\0';
  const CommandResult r = run_physarum("sweep " + quoted(dir.path / "s") + " --job 0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("inputs/files/sign.png: changed since the sweep was planned"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "s" / "run_0000"));
}

}  // namespace
}  // namespace physarum::testing
