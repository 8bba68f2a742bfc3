// A reaction-diffusion system's entry in the table of models (paper 002;
// common/scene/scene_reaction_diffusion.hpp): the refined input surface, the system built on it and
// its maps (its time scales are its own: explicit sub-steps), `physarum run`'s front end
// (api/run/run_reaction_diffusion.cpp) and its harness (api/compare/reaction_diffusion_comparison.cpp).
#include "api/models/model_table.hpp"

#include "api/compare/comparison_model.hpp"
#include "api/run/prepared_run.hpp"
#include "api/session.hpp"
#include "common/base/errors.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/setup/reaction_diffusion_build.hpp"

#include <algorithm>

namespace physarum {
namespace {

ModelBackend build(const Scene& given, const FeasibleSurface& feasible, const ChosenBackend& chosen,
                   const SessionOptions& options) {
  ModelBackend built;
  built.scene = given;
  const ReactionDiffusionSpec& spec = *given.reaction_diffusion();
  ReactionDiffusionSystem system = build_reaction_diffusion_system(given, feasible.surface, feasible.maps);
  built.layer_names = system.morphogens;
  built.substeps = system.substeps;
  built.preview_layer = spec.morphogen_index(spec.preview_morphogen);
  if (system.integrator == Integrator::Forward && system.substeps > 1 && options.log)
    options.log("physarum: " + std::to_string(system.substeps) +
                " explicit sub-steps per step (the diffusion stability limit)");
  const opencl::ComputeContext* compute = chosen.compute ? &*chosen.compute : nullptr;
  built.backend = make_reaction_diffusion_backend(chosen.backend, compute, feasible.surface.domain, std::move(system),
                                                  options.opencl);
  return built;
}

// A coefficient of the kinetics ("parameters.F") as a number over the whole surface: the formulas
// read it at every step. Everything else (morphogens, their diffusion and initial state, the
// integrator, the surface) sets up the system the run started with.
void set_coefficient(Scene& scene, const std::string& key, const nlohmann::json& value) {
  ReactionDiffusionSpec& spec = *scene.reaction_diffusion();
  const std::string prefix = "parameters.";
  if (key.rfind(prefix, 0) != 0)
    throw InputError(key + ": needs a new run (a reaction-diffusion system takes its coefficients on the fly, "
                     "parameters.NAME; this key sets up the system the run started with)");
  const std::string name = key.substr(prefix.size());
  auto it = std::find_if(spec.coefficients.begin(), spec.coefficients.end(), [&](const auto& c) { return c.first == name; });
  if (it == spec.coefficients.end()) throw InputError(key + ": " + spec.model + " has no coefficient '" + name + "'");
  if (!value.is_number()) throw InputError(key + ": expected a number, got " + value.dump());
  it->second = value.get<double>();
}

std::unique_ptr<SimulationBackend> backend_on(BackendChoice backend, const opencl::ComputeContext* compute,
                                              const PreparedSurface& surface, const Scene& scene,
                                              const opencl::OpenCLBackendOptions& options) {
  const EvaluatedMaps maps = evaluate_maps(scene.maps, surface, scene.source);
  return make_reaction_diffusion_backend(backend, compute, surface.domain,
                                         build_reaction_diffusion_system(scene, surface, maps), options);
}

}  // namespace

ModelEntry reaction_diffusion_model_entry() {
  ModelEntry e;
  e.name = "a reaction-diffusion system";
  e.surface = [](const Scene& scene, const Say& say) { return prepare_scene_surface(scene, say); };
  e.build = &build;
  e.backend_on = &backend_on;
  e.set_on_the_fly = &set_coefficient;
  e.prepare_run = &prepare_reaction_diffusion_run;
  e.comparison = &reaction_diffusion_comparison();
  return e;
}

}  // namespace physarum
