// The growth model's entry in the table of models (paper 003; common/scene/scene_growth.hpp): the
// mesh's own triangles at rest as its sheet, a GrowthSimulation (api/growth_simulation.hpp) that runs
// its reaction-diffusion on either backend between growth steps, `physarum run`'s front end
// (api/run/run_growth.cpp) and its schedule as the run's length. No make_backend on a caller's
// surface and no harness: the sheet changes shape as it grows.
#include "api/models/model_table.hpp"

#include "api/growth_simulation.hpp"
#include "api/run/prepared_run.hpp"
#include "api/run/run_options.hpp"
#include "api/session.hpp"
#include "common/base/errors.hpp"
#include "common/setup/growing_sheet_surface.hpp"

namespace physarum {
namespace {

ModelBackend build(const Scene& given, const FeasibleSurface& feasible, const ChosenBackend& chosen,
                   const SessionOptions& options) {
  ModelBackend built;
  built.scene = given;
  const GrowthSpec& spec = *given.growth();
  const opencl::ComputeContext* compute = chosen.compute ? &*chosen.compute : nullptr;
  const BackendChoice choice = chosen.backend;
  const opencl::OpenCLBackendOptions opencl = options.opencl;
  auto make = [choice, compute, opencl](const SurfaceDomain& domain, ReactionDiffusionSystem system) {
    return make_reaction_diffusion_backend(choice, compute, domain, std::move(system), opencl);
  };
  auto growth = std::make_unique<GrowthSimulation>(given, feasible.surface, feasible.maps, make);
  for (const MorphogenSpec& m : spec.reaction.morphogens) built.layer_names.push_back(m.name);
  built.preview_layer = spec.reaction.morphogen_index(spec.reaction.preview_morphogen);
  built.substeps = growth->substeps();
  built.growth = growth.get();
  built.backend = std::move(growth);
  return built;
}

// The schedule; --steps may only restate it (scripts that pass --steps to every run).
long long schedule_length(const RunOptions& o, const Scene& scene) {
  const long long schedule = scene.growth()->schedule.total_steps();
  if ((o.steps && *o.steps != schedule) || o.sim_time)
    throw UsageError(std::string(o.steps ? "--steps" : "--sim-time") + ": a growth scene's length is its schedule (" +
                     std::to_string(schedule) + " steps here: --set schedule.growth_steps=G, "
                     "--set schedule.reaction_steps=N)");
  return schedule;
}

}  // namespace

ModelEntry growth_model_entry() {
  ModelEntry e;
  e.name = "the growth model";
  // It simulates on its mesh's own triangles at rest (common/setup/growing_sheet_surface.hpp).
  e.surface = [](const Scene& scene, const Say&) { return sheet_surface(initial_sheet(scene), scene.mesh); };
  e.build = &build;
  e.why_no_backend_on = "a growth scene's backend grows its sheet between steps: build it with Session "
                        "(api/session.hpp), not make_backend";
  e.prepare_run = &prepare_growth_run;
  e.own_run_length = &schedule_length;
  e.why_not_compared = "physarum compare measures the agent model and reaction-diffusion; a growth scene's sheet "
                       "changes shape as it grows, and the harness has no metrics for it (compare its "
                       "reaction-diffusion as a scene of its own)";
  return e;
}

}  // namespace physarum
