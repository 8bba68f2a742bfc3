#pragma once
// A scene's run as `physarum run` makes it, ready for its first step: the library session (surface,
// maps, backend), what its model writes (a ModelRun), the run loop's setup and the loop itself.
// `physarum run` steps it to the end and writes; the Python module's Simulation steps it as its
// caller asks, reads its fields and writes when asked. One loop for both, so the same steps give the
// same files.
#include "api/session.hpp"
#include "common/output/texture_bake.hpp"
#include "common/output/time_lapse.hpp"
#include "api/run/resume_point.hpp"
#include "api/run/run_loop.hpp"
#include "api/run/run_options.hpp"

#include <functional>
#include <memory>
#include <optional>

namespace physarum {

class PreparedRun {
 public:
  virtual ~PreparedRun();
  PreparedRun(const PreparedRun&) = delete;
  PreparedRun& operator=(const PreparedRun&) = delete;

  Session& session() { return session_; }
  const Session& session() const { return session_; }
  RunLoop& loop() { return *loop_; }
  const RunLoop& loop() const { return *loop_; }
  const RunOptions& options() const { return options_; }
  long long steps() const { return steps_; }
  const ModelRun& model() const { return model_; }

 protected:
  // Builds the time-lapse and the session (everything that can refuse the scene happens here or in
  // the model's preparation, before any output).
  PreparedRun(const Scene& scene, const RunOptions& options, long long steps, const std::optional<ResumePoint>& resume);
  // A model's preparation ends here, its ModelRun filled in: --maps-out is written, and the loop
  // starts on `surface` (a resumed run's checkpoint is restored).
  void start(const PreparedSurface& surface, const FullResolutionMesh& full, std::optional<TexelLocations> texels);

  const RunOptions options_;
  const long long steps_;
  const std::optional<ResumePoint> resume_;
  TimeLapse time_lapse_;
  Session session_;
  ModelRun model_;

 private:
  std::optional<TexelLocations> texels_;
  std::optional<RunSetup> setup_;
  std::unique_ptr<RunLoop> loop_;
};

// The run's length in steps: a growth scene's schedule (--steps may only restate it), else --steps,
// --sim-time, the scene's steps, its sim_time; UsageError when none gives one.
long long run_length_in_steps(const RunOptions& options, const Scene& scene);

// The run of `scene` (loaded, with the options' overrides and seed) for `steps` steps, by its model:
// the agent model (api/run/agent_run.cpp), a reaction-diffusion system
// (run_reaction_diffusion.cpp) or the growth model (run_growth.cpp).
std::unique_ptr<PreparedRun> prepare_run(const Scene& scene, const RunOptions& options, long long steps,
                                         const std::optional<ResumePoint>& resume);

// A run from its options to its files, as `physarum run` makes it: the scene (options.scene) loaded
// with the options' overrides and seed, every check, every step (`progress(done, total)` after each;
// may be empty), every output into options.out. `resume` continues a stopped run from its checkpoint.
RunWritten run_to_files(const RunOptions& options, const std::optional<ResumePoint>& resume = std::nullopt,
                        const std::function<void(long long done, long long total)>& progress = {});

// One model's preparation (each in its model's file).
std::unique_ptr<PreparedRun> prepare_agent_run(const Scene& scene, const RunOptions& options, long long steps,
                                               const std::optional<ResumePoint>& resume);
std::unique_ptr<PreparedRun> prepare_reaction_diffusion_run(const Scene& scene, const RunOptions& options,
                                                            long long steps, const std::optional<ResumePoint>& resume);
std::unique_ptr<PreparedRun> prepare_growth_run(const Scene& scene, const RunOptions& options, long long steps,
                                                const std::optional<ResumePoint>& resume);

}  // namespace physarum
