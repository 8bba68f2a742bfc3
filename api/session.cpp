#include "api/session.hpp"

#include "api/live_backend.hpp"
#include "api/models/model_table.hpp"
#include "common/base/errors.hpp"

#include "common/base/content_hash.hpp"
#include "common/maps/map_cache.hpp"
#include "common/run/checkpoint.hpp"
#include "common/scene/scene_json.hpp"
#include "common/surface/field_transfer.hpp"

#include <utility>

namespace physarum {

struct SessionParts {
  Scene given;  // the scene as given (live changes apply to it)
  SessionOptions options;
  FeasibleSurface feasible;
  ChosenBackend chosen;  // owns the compute context the backend uses: kept before it (destroyed after)
  ModelBackend model;    // the scene as simulated, its layers (its backend is in `live`)
  std::unique_ptr<LiveBackend> live;
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
  j["model"] = model_json(scene);
  return hex64(content_hash(j.dump()));
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
  p.given = scene;
  p.options = options;
  p.model = model_entry(scene).build(scene, p.feasible, p.chosen, options);
  p.live = std::make_unique<LiveBackend>(std::move(p.model.backend));
  p.scene_hash = scene_identity(p.model.scene, p.feasible.surface);
}

Session::~Session() = default;
Session::Session(Session&&) noexcept = default;
Session& Session::operator=(Session&&) noexcept = default;

const Scene& Session::scene() const { return parts_->model.scene; }
const PreparedSurface& Session::surface() const { return parts_->feasible.surface; }
const PreparedSurface& Session::surface_now() const {
  return parts_->model.growth ? parts_->model.growth->surface() : parts_->feasible.surface;
}
const EvaluatedMaps& Session::maps() const { return parts_->feasible.maps; }
const MapEvaluationReport& Session::maps_report() const { return parts_->feasible.maps_report; }
const SceneArrays* Session::agent_arrays() const { return parts_->model.arrays ? &*parts_->model.arrays : nullptr; }
BackendChoice Session::backend_choice() const { return parts_->chosen.backend; }
const std::string& Session::backend_reason() const { return parts_->chosen.why; }
SimulationBackend& Session::backend() { return *parts_->live; }
const SimulationBackend& Session::backend() const { return *parts_->live; }
const std::vector<std::string>& Session::layer_names() const { return parts_->model.layer_names; }
int Session::preview_layer() const { return parts_->model.preview_layer; }
int Session::substeps() const { return parts_->model.substeps; }
GrowthSimulation* Session::growth() { return parts_->model.growth; }
const GrowthSimulation* Session::growth() const { return parts_->model.growth; }

void Session::step(long long steps) { parts_->live->run(steps); }
double Session::time() const { return parts_->live->time(); }
long long Session::steps_taken() const { return parts_->live->steps_taken(); }

IntrinsicVertexData<double> Session::field(int layer) const { return parts_->live->field_values(layer); }

InputVertexData<double> Session::field_on_input(int layer) const {
  const PreparedSurface& s = surface();
  if (parts_->model.growth) {  // the input's vertices are the sheet's first ones, wherever the sheet went
    const IntrinsicVertexData<double> all = field(layer);
    return InputVertexData<double>(std::vector<double>(all.begin(), all.begin() + s.input.vertex_count()));
  }
  return intrinsic_to_input(s.input, s.domain.vertex_location, field(layer));
}

void Session::set_field(const IntrinsicVertexData<double>& values, int layer) { parts_->live->set_field(values, layer); }

void Session::set_field_on_input(const InputVertexData<double>& values, int layer) {
  const PreparedSurface& s = surface();
  if (parts_->model.growth) {  // the sheet's own vertices: the input's until the sheet is refined
    set_field(IntrinsicVertexData<double>(std::vector<double>(values.begin(), values.end())), layer);
    return;
  }
  set_field(input_to_intrinsic(s.input, s.domain.vertex_location, values), layer);
}

long long Session::set(const std::string& key, const nlohmann::json& value) {
  SessionParts& p = *parts_;
  const ModelEntry& model = model_entry(p.given);
  const std::string where = (p.given.source.empty() ? std::string("scene") : p.given.source) + ": ";
  if (!model.set_on_the_fly)
    throw InputError(where + key + ": needs a new run (" + model.name + " takes no key on the fly; --set " + key +
                     "=... starts one)");
  Scene changed = p.given;
  try {
    model.set_on_the_fly(changed, key, value);
  } catch (const InputError& e) {
    throw InputError(where + e.what());
  }
  validate_scene(changed);  // its messages name the scene and the key themselves
  // A backend of the changed scene, continuing from the state now (nothing changes if building fails).
  ModelBackend next = model.build(changed, p.feasible, p.chosen, p.options);
  p.live->replace(std::move(next.backend));
  p.model = std::move(next);
  p.given = std::move(changed);
  p.scene_hash = scene_identity(p.model.scene, p.feasible.surface);
  return steps_taken();
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
