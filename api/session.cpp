#include "api/session.hpp"

#include "common/base/content_hash.hpp"
#include "common/base/overloaded.hpp"
#include "common/maps/map_cache.hpp"
#include "common/run/checkpoint.hpp"
#include "common/scene/scene_json.hpp"
#include "common/setup/reaction_diffusion_build.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/surface/field_transfer.hpp"

#include <utility>

namespace physarum {

struct SessionParts {
  Scene scene;
  FeasibleSurface feasible;
  std::optional<SceneArrays> arrays;  // the agent model's
  ChosenBackend chosen;               // owns the compute context the backend uses: kept beside it
  std::unique_ptr<SimulationBackend> backend;
  GrowthSimulation* growth = nullptr;  // the backend, for a growth scene
  std::vector<std::string> layer_names;
  int preview_layer = 0;
  int substeps = 1;
  std::string scene_hash;
};

namespace {

// What a checkpoint's "scene" identity covers: the surface's keys and size, the run's time step and
// seed, and the model's whole description.
std::string scene_identity(const Scene& scene, const PreparedSurface& surface) {
  nlohmann::ordered_json j;
  j["mesh"] = scene.mesh;
  j["input"] = {surface.input.vertex_count(), surface.input.triangle_count()};
  j["faces"] = surface.domain.face_count;
  j["time_step"] = scene.time_step;
  j["seed"] = scene.seed;
  j["maps"] = scene.maps_given;
  std::visit(overloaded{[&](const AgentModelSpec&) { j["model"] = scene_parameters_json(scene); },
                        [&](const ReactionDiffusionSpec& system) { j["model"] = reaction_diffusion_json(system); },
                        [&](const GrowthSpec& growth) { j["model"] = growth_json(growth); }},
             scene.model);
  return hex64(content_hash(j.dump()));
}

void build_agent_backend(SessionParts& p, const Scene& given, const SessionOptions& options) {
  const SurfaceDomain& domain = p.feasible.surface.domain;
  p.arrays = scene_arrays(given, p.feasible.surface, p.feasible.maps);
  p.scene = with_mean_parameters(given, p.arrays->parameters, domain);
  const opencl::ComputeContext* compute = p.chosen.compute ? &*p.chosen.compute : nullptr;
  // make_backend refuses what does not fit in memory before it allocates.
  p.backend = make_backend(p.chosen.backend, compute, domain, p.scene, *p.arrays, options.opencl);
  const int layers = p.backend->dynamic_layer_count();
  if (layers == 1) p.layer_names = {"pheromone"};
  for (int layer = 0; layers > 1 && layer < layers; ++layer) p.layer_names.push_back("pheromone_" + std::to_string(layer));
}

void build_reaction_diffusion_backend(SessionParts& p, const Scene& given, const SessionOptions& options) {
  p.scene = given;
  const ReactionDiffusionSpec& spec = *given.reaction_diffusion();
  ReactionDiffusionSystem system = build_reaction_diffusion_system(given, p.feasible.surface, p.feasible.maps);
  p.layer_names = system.morphogens;
  p.substeps = system.substeps;
  p.preview_layer = spec.morphogen_index(spec.preview_morphogen);
  if (system.integrator == Integrator::Forward && system.substeps > 1 && options.log)
    options.log("physarum: " + std::to_string(system.substeps) +
                " explicit sub-steps per step (the diffusion stability limit)");
  const opencl::ComputeContext* compute = p.chosen.compute ? &*p.chosen.compute : nullptr;
  p.backend = make_reaction_diffusion_backend(p.chosen.backend, compute, p.feasible.surface.domain, std::move(system),
                                              options.opencl);
}

void build_growth_backend(SessionParts& p, const Scene& given, const SessionOptions& options) {
  p.scene = given;
  const GrowthSpec& spec = *given.growth();
  const opencl::ComputeContext* compute = p.chosen.compute ? &*p.chosen.compute : nullptr;
  const BackendChoice choice = p.chosen.backend;
  const opencl::OpenCLBackendOptions opencl = options.opencl;
  auto make = [choice, compute, opencl](const SurfaceDomain& domain, ReactionDiffusionSystem system) {
    return make_reaction_diffusion_backend(choice, compute, domain, std::move(system), opencl);
  };
  auto growth = std::make_unique<GrowthSimulation>(given, p.feasible.surface, p.feasible.maps, make);
  for (const MorphogenSpec& m : spec.reaction.morphogens) p.layer_names.push_back(m.name);
  p.preview_layer = spec.reaction.morphogen_index(spec.reaction.preview_morphogen);
  p.substeps = growth->substeps();
  p.growth = growth.get();
  p.backend = std::move(growth);
}

}  // namespace

Session::Session(const Scene& scene, const SessionOptions& options) : parts_(std::make_unique<SessionParts>()) {
  SessionParts& p = *parts_;
  const MapCache cache = options.use_map_cache ? MapCache::from_environment() : MapCache::disabled();
  p.feasible = prepare_feasible_surface(scene, std::max(options.planned_steps, 1LL), cache, options.log);
  if (options.log && !scene.maps.empty()) {
    for (const std::string& note : p.feasible.maps_report.notes) options.log("physarum: " + note);
    options.log("physarum: " + p.feasible.maps_report.summary());
  }
  p.chosen = choose_backend(options.backend, options.device);
  if (options.backend == "auto" && options.log)
    options.log("physarum: " + std::string(to_string(p.chosen.backend)) + " backend (auto: " + p.chosen.why + ")");
  std::visit(overloaded{[&](const AgentModelSpec&) { build_agent_backend(p, scene, options); },
                        [&](const ReactionDiffusionSpec&) { build_reaction_diffusion_backend(p, scene, options); },
                        [&](const GrowthSpec&) { build_growth_backend(p, scene, options); }},
             scene.model);
  p.scene_hash = scene_identity(p.scene, p.feasible.surface);
}

Session::~Session() = default;
Session::Session(Session&&) noexcept = default;
Session& Session::operator=(Session&&) noexcept = default;

const Scene& Session::scene() const { return parts_->scene; }
const PreparedSurface& Session::surface() const { return parts_->feasible.surface; }
const EvaluatedMaps& Session::maps() const { return parts_->feasible.maps; }
const MapEvaluationReport& Session::maps_report() const { return parts_->feasible.maps_report; }
const SceneArrays* Session::agent_arrays() const { return parts_->arrays ? &*parts_->arrays : nullptr; }
BackendChoice Session::backend_choice() const { return parts_->chosen.backend; }
const std::string& Session::backend_reason() const { return parts_->chosen.why; }
SimulationBackend& Session::backend() { return *parts_->backend; }
const SimulationBackend& Session::backend() const { return *parts_->backend; }
const std::vector<std::string>& Session::layer_names() const { return parts_->layer_names; }
int Session::preview_layer() const { return parts_->preview_layer; }
int Session::substeps() const { return parts_->substeps; }
GrowthSimulation* Session::growth() { return parts_->growth; }
const GrowthSimulation* Session::growth() const { return parts_->growth; }

void Session::step(long long steps) { parts_->backend->run(steps); }
double Session::time() const { return parts_->backend->time(); }
long long Session::steps_taken() const { return parts_->backend->steps_taken(); }

IntrinsicVertexData<double> Session::field(int layer) const { return parts_->backend->field_values(layer); }

InputVertexData<double> Session::field_on_input(int layer) const {
  const PreparedSurface& s = surface();
  if (parts_->growth) {  // the input's vertices are the sheet's first ones, wherever the sheet went
    const IntrinsicVertexData<double> all = field(layer);
    return InputVertexData<double>(std::vector<double>(all.begin(), all.begin() + s.input.vertex_count()));
  }
  return intrinsic_to_input(s.input, s.domain.vertex_location, field(layer));
}

void Session::set_field(const IntrinsicVertexData<double>& values, int layer) { parts_->backend->set_field(values, layer); }

void Session::set_field_on_input(const InputVertexData<double>& values, int layer) {
  const PreparedSurface& s = surface();
  if (parts_->growth) {  // the sheet's own vertices: the input's until the sheet is refined
    set_field(IntrinsicVertexData<double>(std::vector<double>(values.begin(), values.end())), layer);
    return;
  }
  set_field(input_to_intrinsic(s.input, s.domain.vertex_location, values), layer);
}

void Session::save(const std::string& path) const {
  CheckpointHeader header{checkpoint_build_id(), backend().backend_name(), backend().device_name(), parts_->scene_hash,
                          steps_taken(), nlohmann::json::object()};
  write_checkpoint(path, header, backend().save_state());
}

void Session::restore(const std::string& path) {
  const Checkpoint saved = read_checkpoint(path);
  const CheckpointHeader identity{checkpoint_build_id(), backend().backend_name(), backend().device_name(),
                                  parts_->scene_hash, saved.header.step, nlohmann::json::object()};
  check_checkpoint_matches(saved.header, identity, path);
  backend().restore_state(saved.state);
}

}  // namespace physarum
