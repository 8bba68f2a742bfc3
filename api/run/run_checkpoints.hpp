#pragma once
// The checkpoints of one `physarum run`, for every model's run (api/run/agent_run.cpp,
// api/run/run_reaction_diffusion.cpp): what identifies the run (build, backend, device, scene), where a
// resumed run starts (its backend restored, its statistics text and simulated seconds so far taken
// from the checkpoint's header), writing DIR/checkpoint.bin every `--checkpoint-every` seconds of
// simulated time (atomically replaced), run.json's record of it, and removing it once the outputs are
// complete. The seconds in a checkpoint are simulation seconds: the loop passes what it spent on
// anything else (statistics rows, frames), and the time spent writing checkpoints is left out here.
#include "common/run/checkpoint.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "api/run/resume_point.hpp"
#include "api/run/run_options.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace physarum {

class RunCheckpoints {
 public:
  // `mesh` and `time_step` are the scene's (the identity hash and the interval in steps). With
  // `resume`: checks that it is this run's (InputError otherwise, or when it is at or past `steps`),
  // restores `simulation` from it and says so on stderr. Creates the output folder when checkpoints
  // will be written.
  RunCheckpoints(SimulationBackend& simulation, const RunOptions& o, const std::string& mesh, double time_step, long long steps,
                 const std::optional<ResumePoint>& resume);

  long long first_step() const { return first_step_; }
  // The statistics text so far of a resumed run (null for a fresh one).
  const std::string* resumed_stats() const { return resumed_stats_ ? &*resumed_stats_ : nullptr; }

  // Call once when the loop starts, then after every step s with the statistics text so far and the
  // seconds the loop spent since the start on anything but simulating: writes a checkpoint when one
  // is due (s a multiple of the interval, before the last step).
  void start() { start_ = std::chrono::steady_clock::now(); }
  void after_step(long long s, const SimulationBackend& simulation, const std::string& stats, double side_seconds);
  // The simulation seconds of the whole run (those before a resumed checkpoint included) at the end
  // of the loop, given its side seconds.
  double simulation_seconds(double side_seconds) const;

  // What identifies this run in a checkpoint (build, backend, device, scene), for a caller that keeps
  // the state itself (the Python module's save_state / restore_state).
  const CheckpointHeader& identity() const { return identity_; }

  // "resumed_from_step" and "checkpoints" into run.json, then the checkpoint removed: the outputs are
  // complete, so it has nothing left to protect.
  void record(nlohmann::ordered_json& run_json) const;
  void remove_file() const;

 private:
  const RunOptions& options_;
  long long steps_ = 0, interval_ = 0, first_step_ = 1;
  std::optional<long long> resumed_from_;
  std::optional<std::string> resumed_stats_;
  CheckpointHeader identity_;
  std::filesystem::path path_;
  double seconds_before_ = 0.0;  // simulation seconds of the run before its checkpoint
  std::chrono::steady_clock::time_point start_;
  long long written_ = 0;
  double writing_seconds_ = 0.0;
  std::size_t bytes_ = 0;
};

}  // namespace physarum
