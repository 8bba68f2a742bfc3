// The agent model's entry in the table of models (paper 000; common/scene/scene_agents.hpp): the
// refined input surface, the time-scale and work checks, its backend on either side, `physarum run`'s
// agent front end (api/run/agent_run.cpp) and the agent harness (api/compare/agent_comparison.cpp).
#include "api/models/model_table.hpp"

#include "api/compare/comparison_model.hpp"
#include "api/run/prepared_run.hpp"
#include "api/session.hpp"
#include "common/base/errors.hpp"
#include "common/model/agent_model.hpp"
#include "common/setup/run_feasibility.hpp"
#include "common/setup/scene_maps.hpp"

#include <limits>
#include <unistd.h>

namespace physarum {
namespace {

// About ten seconds of work and more (1e9 elementary operations a second at best).
constexpr double kLongRunOperations = 1e10;

void check_scales(const Scene& scene, const Say& say) {
  for (const std::string& w : check_time_scales(scene, kMaxTurnDecisionsPerStep))
    if (say) say("physarum: warning: " + w);
}

// Without parameter maps the time scales are known before the surface: checked first, as a bad
// time step is cheaper to refuse than a refinement is to wait for.
void check_before_surface(const Scene& scene, const Say& say) {
  if (!has_parameter_maps(scene)) check_scales(scene, say);
}

// With parameter maps, each mapped parameter's mean over the surface stands for it; then the run's work.
void check_on_surface(const Scene& given, const FeasibleSurface& feasible, long long steps, const Say& say) {
  const PreparedSurface& surface = feasible.surface;
  const bool mapped = has_parameter_maps(given);
  const Scene scene =
      mapped ? with_mean_parameters(given, vertex_parameters(given, surface, feasible.maps), surface.domain) : given;
  if (mapped) check_scales(scene, say);
  const WorkEstimate work = estimate_work(scene, surface.domain, surface.diameter, steps, kMaxTurnDecisionsPerStep);
  // On a terminal always; in a log only for a long run (a quiet log stays empty on a short one).
  if (say && (::isatty(STDERR_FILENO) == 1 || work.operations >= kLongRunOperations)) say(work.describe());
  check_work(scene, work);
}

ModelBackend build(const Scene& given, const FeasibleSurface& feasible, const ChosenBackend& chosen,
                   const SessionOptions& options) {
  ModelBackend built;
  const SurfaceDomain& domain = feasible.surface.domain;
  built.arrays = scene_arrays(given, feasible.surface, feasible.maps);
  built.scene = with_mean_parameters(given, built.arrays->parameters, domain);
  const opencl::ComputeContext* compute = chosen.compute ? &*chosen.compute : nullptr;
  // make_backend refuses what does not fit in memory before it allocates.
  built.backend = make_backend(chosen.backend, compute, domain, built.scene, *built.arrays, options.opencl);
  const int layers = built.backend->dynamic_layer_count();
  if (layers == 1) built.layer_names = {"pheromone"};
  for (int layer = 0; layers > 1 && layer < layers; ++layer) built.layer_names.push_back("pheromone_" + std::to_string(layer));
  return built;
}

// A parameter of Table 1 as a number (null: +infinity where the key allows it), for the whole
// surface: a map it was given is replaced. Everything else (the agent count, species, controls, the
// surface, the time step) places or sizes what the run started with.
void set_parameter(Scene& scene, const std::string& key, const nlohmann::json& value) {
  const ParameterSpec* spec = nullptr;
  for (const ParameterSpec& p : kParameterTable)
    if (p.key == key) spec = &p;
  AgentModelSpec& model = scene.agent_model();
  if (!spec)
    throw InputError(key + ": needs a new run (the agent model takes its Table 1 parameters on the fly: "
                     "sensor_angle, deposit_rate, ...; this key places or sizes what the run started with)");
  if (!model.species.species.empty())
    throw InputError(key + ": needs a new run (a competing-species scene's parameters are its species')");
  double file_value = 0.0;
  if (value.is_number()) file_value = value.get<double>();
  else if (value.is_null() && spec->null_means_infinite) file_value = std::numeric_limits<double>::infinity();
  else throw InputError(key + ": expected a number" + (spec->null_means_infinite ? " or null" : "") + ", got " + value.dump());
  model.parameters[spec->id] = file_value * spec->file_to_si;
  model.parameter_maps[static_cast<size_t>(spec->id)].reset();
}

std::unique_ptr<SimulationBackend> backend_on(BackendChoice backend, const opencl::ComputeContext* compute,
                                              const PreparedSurface& surface, const Scene& scene,
                                              const opencl::OpenCLBackendOptions& options) {
  return make_backend(backend, compute, surface.domain, scene, scene_arrays(scene, surface), options);
}

}  // namespace

ModelEntry agent_model_entry() {
  ModelEntry e;
  e.name = "the agent model";
  e.surface = [](const Scene& scene, const Say& say) { return prepare_scene_surface(scene, say); };
  e.check_before_surface = &check_before_surface;
  e.check_on_surface = &check_on_surface;
  e.build = &build;
  e.backend_on = &backend_on;
  e.set_on_the_fly = &set_parameter;
  e.prepare_run = &prepare_agent_run;
  e.comparison = &agent_comparison();
  return e;
}

}  // namespace physarum
