// `physarum run --checkpoint-every T` and `physarum run --resume DIR` as a user meets them: a run
// killed with SIGKILL at a random moment and resumed writes byte for byte what the uninterrupted run
// writes (both backends); a corrupted checkpoint and one of another scene are refused with a clear
// message and nothing written.
#include "killed_run.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <fcntl.h>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;

// Small enough for seconds, long enough (a few thousand steps) to be killed mid-way.
const char* kScene = R"({
  "mesh": "shape:sphere", "scale_to_area": 1.0, "agents": 400, "time_step": 0.01,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 0.5, "activation_time": 0.2, "integrator": "forward", "seed": 5
})";
constexpr int kSteps = 2000;

class ResumeCommand : public ResumeFixture {
 protected:
  void SetUp() override { prepare(kScene, kSteps); }
};

TEST_P(ResumeCommand, KilledRunResumesToTheUninterruptedRunsBytes) {
  expect_killed_run_resumes_to_the_same_bytes("0.05", 5);  // every 5 steps
}

TEST_P(ResumeCommand, CorruptedOrForeignCheckpointsAreRefused) {
  const fs::path killed = dir_.path / "killed";
  std::vector<std::string> args = run_args(killed);
  args.insert(args.end(), {"--checkpoint-every", "0.05"});
  ASSERT_TRUE(run_and_kill(args, killed / "checkpoint.bin", 7));
  const std::string good = bytes_of(killed / "checkpoint.bin");

  // One flipped byte in the middle of the state.
  std::string bad = good;
  bad[bad.size() / 2] = static_cast<char>(bad[bad.size() / 2] ^ 0x01);
  std::ofstream(killed / "checkpoint.bin", std::ios::binary) << bad;
  const CommandResult corrupted = run_physarum("run --resume " + quoted(killed));
  EXPECT_EQ(corrupted.exit_code, 1);
  EXPECT_NE(corrupted.err.find("corrupted"), std::string::npos) << corrupted.err;
  EXPECT_FALSE(fs::exists(killed / "run.json"));

  // Another scene (the same file with one parameter changed) given with the checkpoint.
  std::ofstream(killed / "checkpoint.bin", std::ios::binary) << good;
  std::string other = kScene;
  other.replace(other.find("\"deposit_rate\": 1.0"), 19, "\"deposit_rate\": 2.0");
  std::ofstream(dir_.path / "other.json") << other;
  const CommandResult foreign = run_physarum("run " + quoted(dir_.path / "other.json") + " --resume " + quoted(killed));
  EXPECT_EQ(foreign.exit_code, 1);
  EXPECT_NE(foreign.err.find("another scene"), std::string::npos) << foreign.err;
  EXPECT_FALSE(fs::exists(killed / "run.json"));

  // The intact checkpoint still resumes.
  EXPECT_EQ(run_physarum("run --resume " + quoted(killed)).exit_code, 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, ResumeCommand, ::testing::Values("reference", "opencl"));

}  // namespace
}  // namespace physarum::testing
