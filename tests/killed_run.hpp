#pragma once
// A run stopped the hard way, for the resume tests (test_cli_resume*.cpp): `physarum` started in a
// child process and SIGKILLed a random while after its first checkpoint appears, so the stop can
// fall anywhere, a checkpoint write included; and a file's bytes, to compare a resumed run's outputs
// with the uninterrupted run's.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace physarum::testing {

inline std::string bytes_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Starts `physarum ARGS...` (output discarded) and SIGKILLs it a random while after its first
// checkpoint appears. Returns false when it finished before the kill.
inline bool run_and_kill(const std::vector<std::string>& args, const std::filesystem::path& checkpoint, unsigned seed) {
  std::vector<std::string> words{PHYSARUM_EXE};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls before exec: this test process may hold OpenCL's threads.
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(checkpoint) && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::mt19937 random(seed);
  std::this_thread::sleep_for(std::chrono::milliseconds(std::uniform_int_distribution<int>(0, 150)(random)));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

// The fixture of both models' resume suites, parameterised by backend: DIR/scene.json (the suite's
// scene), a one-step probe run that skips the OpenCL case where there is no device, and the
// arguments of a `steps`-step run of the scene into a folder.
class ResumeFixture : public ::testing::TestWithParam<std::string> {
 protected:
  void prepare(const std::string& scene, long long steps) {
    steps_ = steps;
    std::ofstream(dir_.path / "scene.json") << scene;
    const CommandResult probe = run_physarum("run " + quoted(dir_.path / "scene.json") + " --backend " + GetParam() +
                                             " --steps 1 --texture-size 16 --out " + quoted(dir_.path / "probe"));
    if (probe.exit_code != 0 && probe.err.find("device error") != std::string::npos)
      GTEST_SKIP() << "no OpenCL device: " << probe.err;
    ASSERT_EQ(probe.exit_code, 0) << probe.err;
  }
  std::vector<std::string> run_args(const std::filesystem::path& out) const {
    return {"run", (dir_.path / "scene.json").string(), "--backend", GetParam(), "--steps", std::to_string(steps_),
            "--texture-size", "16", "--out", out.string()};
  }
  // The resume contract: the scene run whole; the same with --checkpoint-every `every` (a checkpoint
  // every `steps_per_checkpoint` steps) killed at a random moment and resumed writes the same bytes,
  // records a resume step in (0, steps) that is a multiple of `steps_per_checkpoint`, and removes its
  // checkpoint.
  void expect_killed_run_resumes_to_the_same_bytes(const std::string& every, long long steps_per_checkpoint) {
    namespace fs = std::filesystem;
    std::string whole_args;
    for (const std::string& a : run_args(dir_.path / "whole")) whole_args += quoted(fs::path(a)) + " ";
    const CommandResult whole = run_physarum(whole_args);
    ASSERT_EQ(whole.exit_code, 0) << whole.err;

    const unsigned seed = std::random_device{}();
    const fs::path killed = dir_.path / "killed";
    std::vector<std::string> args = run_args(killed);
    args.insert(args.end(), {"--checkpoint-every", every});
    ASSERT_TRUE(run_and_kill(args, killed / "checkpoint.bin", seed))
        << "the run finished before it could be killed (kill delay seed " << seed << ")";
    ASSERT_TRUE(fs::exists(killed / "checkpoint.bin"));
    ASSERT_FALSE(fs::exists(killed / "run.json"));

    const CommandResult resumed = run_physarum("run --resume " + quoted(killed));
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    for (const char* file : {"pheromone.ply", "fields_full.ply", "stats.csv", "preview.png"})
      EXPECT_TRUE(bytes_of(killed / file) == bytes_of(dir_.path / "whole" / file))
          << file << " differs from the uninterrupted run's (kill delay seed " << seed << ")";
    std::ifstream in(killed / "run.json");
    const auto j = nlohmann::json::parse(in);
    const long long from = j["resumed_from_step"].get<long long>();
    EXPECT_GT(from, 0);
    EXPECT_LT(from, steps_);
    EXPECT_EQ(from % steps_per_checkpoint, 0);
    EXPECT_EQ(j["steps"], steps_);
    EXPECT_FALSE(fs::exists(killed / "checkpoint.bin")) << "a finished run removes its checkpoint";
  }
  TempDir dir_;
  long long steps_ = 0;
};

}  // namespace physarum::testing
