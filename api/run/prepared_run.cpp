#include "api/run/prepared_run.hpp"

#include "common/base/errors.hpp"
#include "api/models/model_table.hpp"
#include "common/output/maps_ply.hpp"
#include "common/setup/scene_maps.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {

PreparedRun::PreparedRun(const Scene& scene, const RunOptions& options, long long steps,
                         const std::optional<ResumePoint>& resume)
    : options_(options),
      steps_(steps),
      resume_(resume),
      time_lapse_(options.frames, steps),
      session_(scene, session_options(options, steps)) {}

PreparedRun::~PreparedRun() = default;

void PreparedRun::start(const PreparedSurface& surface, const FullResolutionMesh& full,
                        std::optional<TexelLocations> texels) {
  // Everything that could refuse the input has run (the model's preparation too): --maps-out is
  // written now, before simulating, so a user checking a long run's maps sees them at once.
  const Scene& scene = session_.scene();
  if (!options_.maps_out.empty())
    write_maps_ply(options_.maps_out, session_.surface().input,
                   maps_on_input(scene.maps, session_.surface(), session_.maps(), options_.scene));
  texels_ = std::move(texels);
  setup_.emplace(RunSetup{options_, session_.scene(), steps_, resume_, surface, full, texels_, time_lapse_});
  loop_ = std::make_unique<RunLoop>(session_.backend(), *setup_, model_);
}

long long run_length_in_steps(const RunOptions& o, const Scene& scene) {
  auto steps_for = [&](double seconds) {
    // Nearest whole step: T / dt often lands a rounding error away from an integer.
    return std::max<long long>(1, std::llround(seconds / scene.time_step));
  };
  if (const ModelEntry& model = model_entry(scene); model.own_run_length) return model.own_run_length(o, scene);
  if (o.steps) return *o.steps;
  if (o.sim_time) return steps_for(*o.sim_time);
  if (scene.steps) return *scene.steps;
  if (scene.sim_time) return steps_for(*scene.sim_time);
  throw UsageError("no run length: give --steps N or --sim-time T (or 'steps' / 'sim_time' in " + o.scene + ")");
}

RunWritten run_to_files(const RunOptions& o, const std::optional<ResumePoint>& resume,
                        const std::function<void(long long done, long long total)>& progress) {
  // ---- everything that can reject the input, before any output exists ----
  Scene scene = load_scene(o.scene, o.overrides());
  if (o.seed) scene.seed = *o.seed;
  if (!o.maps_out.empty() && scene.maps.empty()) throw UsageError("--maps-out: " + o.scene + " defines no maps (key 'maps')");
  const std::unique_ptr<PreparedRun> run = prepare_run(scene, o, run_length_in_steps(o, scene), resume);
  RunLoop& loop = run->loop();
  while (loop.step())
    if (progress) progress(loop.steps_taken(), loop.planned_steps());
  return loop.write(o.out);
}

std::unique_ptr<PreparedRun> prepare_run(const Scene& scene, const RunOptions& options, long long steps,
                                         const std::optional<ResumePoint>& resume) {
  return model_entry(scene).prepare_run(scene, options, steps, resume);
}

}  // namespace physarum
