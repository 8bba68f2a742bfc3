#include "api/run/run_checkpoints.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {

RunCheckpoints::RunCheckpoints(SimulationBackend& simulation, const RunOptions& o, const std::string& mesh, double time_step,
                               long long steps, const std::optional<ResumePoint>& resume)
    : options_(o), steps_(steps) {
  identity_.build_id = checkpoint_build_id();
  identity_.backend = simulation.backend_name();
  identity_.device = simulation.device_name();
  identity_.scene_hash = scene_identity_hash(o, mesh);
  path_ = std::filesystem::path(o.out) / "checkpoint.bin";
  interval_ = o.checkpoint_every ? std::max<long long>(1, std::llround(*o.checkpoint_every / time_step)) : 0;
  if (resume) {
    const CheckpointHeader& header = resume->checkpoint.header;
    check_checkpoint_matches(header, identity_, resume->path);
    if (header.step >= steps)
      throw InputError(resume->path + ": the checkpoint is at step " + std::to_string(header.step) + " of " +
                       std::to_string(steps) + ": nothing is left to run");
    simulation.restore_state(resume->checkpoint.state);
    resumed_stats_ = header.run.at("stats").get<std::string>();
    seconds_before_ = header.run.at("seconds").get<double>();
    first_step_ = header.step + 1;
    resumed_from_ = header.step;
    if (o.log)
      o.log("physarum run: resuming " + o.out + " at step " + std::to_string(header.step) + " of " + std::to_string(steps));
  }
  if (interval_ > 0) create_output_folder(o.out);
}

void RunCheckpoints::after_step(long long s, const SimulationBackend& simulation, const std::string& stats, double side_seconds) {
  if (interval_ <= 0 || s % interval_ != 0 || s >= steps_) return;
  const auto now = std::chrono::steady_clock::now();
  CheckpointHeader header = identity_;
  header.step = s;
  header.run = {{"options", run_options_json(options_)},
                {"stats", stats},
                {"seconds", seconds_before_ + std::chrono::duration<double>(now - start_).count() - side_seconds - writing_seconds_}};
  const std::string bytes = checkpoint_bytes(header, simulation.save_state());
  write_text_file_atomically(path_.string(), bytes);
  ++written_;
  bytes_ = bytes.size();
  writing_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - now).count();
}

double RunCheckpoints::simulation_seconds(double side_seconds) const {
  return seconds_before_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() - side_seconds -
         writing_seconds_;
}

void RunCheckpoints::record(nlohmann::ordered_json& j) const {
  if (resumed_from_) j["resumed_from_step"] = *resumed_from_;
  if (interval_ > 0)
    j["checkpoints"] = {{"every_steps", interval_},
                        {"written", written_},
                        {"bytes", bytes_},
                        {"seconds_per_checkpoint", written_ > 0 ? writing_seconds_ / static_cast<double>(written_) : 0.0}};
}

void RunCheckpoints::remove_file() const {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace physarum
