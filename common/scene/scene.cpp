#include "common/scene/scene.hpp"

#include "common/base/errors.hpp"
#include "common/scene/scene_fields.hpp"
#include "common/scene/scene_keys.hpp"
#include "common/scene/scene_overrides.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

namespace physarum {
namespace {

using nlohmann::json;

json parse_scene_text(const std::string& text, const std::string& path) {
  // Duplicate keys are a likely copy-paste mistake and nlohmann silently keeps the last one, so the
  // parser callback watches the keys of the top-level object.
  std::set<std::string> seen;
  std::string duplicate;
  int depth = 0;
  auto callback = [&](int /*callback_depth*/, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) {
      // Refused while parsing: a hostile file is stopped at the limit, not after it is all read.
      if (++depth > kMaxSceneNesting) fail_nesting(path);
    }
    if (event == json::parse_event_t::object_end || event == json::parse_event_t::array_end) --depth;
    if (event == json::parse_event_t::key && depth == 1 && duplicate.empty()) {
      const std::string key = parsed.get<std::string>();
      if (!seen.insert(key).second) duplicate = key;
    }
    return true;
  };
  json j;
  try {
    j = json::parse(text, callback);
  } catch (const json::parse_error& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line L, column C: ..."; keep
    // the part after the bracketed id, which carries the line and column.
    std::string message = e.what();
    if (auto pos = message.find("] "); pos != std::string::npos) message = message.substr(pos + 2);
    throw InputError(path + ": malformed JSON: " + message);
  }
  if (!duplicate.empty()) throw InputError(path + ": key '" + duplicate + "' appears more than once");
  if (!j.is_object())
    throw InputError(path + ": a scene must be one JSON object ({...}), found " + std::string(j.type_name()));
  return j;
}

json read_scene_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the scene file");
  std::stringstream buffer;
  buffer << file.rdbuf();
  if (file.bad()) throw InputError(path + ": cannot read the scene file");
  return parse_scene_text(buffer.str(), path);
}

void refuse_unknown_keys(const json& j, const std::string& where) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (!find_scene_key(it.key()))
      throw InputError(where + ": unknown key '" + it.key() + "' (did you mean '" + closest_scene_key(it.key()) +
                       "'?)");
  }
}

// "mesh": a procedural shape as given, a file resolved against the scene's folder and required to exist.
std::string read_mesh(const SceneReader& read, const std::string& path, const std::filesystem::path& folder) {
  const std::string mesh = *read.string("mesh");
  if (mesh.empty()) throw InputError(path + ": key 'mesh' = \"\" is empty (give a file path or shape:NAME)");
  if (mesh.rfind("shape:", 0) == 0) return mesh;
  std::filesystem::path mesh_path(mesh);
  if (mesh_path.is_relative()) mesh_path = folder / mesh_path;
  mesh_path = mesh_path.lexically_normal();
  if (!std::filesystem::exists(mesh_path))
    throw InputError(path + ": key 'mesh' = \"" + mesh + "\": file not found (looked for " + mesh_path.string() + ")");
  return mesh_path.string();
}

ComparisonSettings read_comparison(const SceneReader& read) {
  ComparisonSettings c;
  c.burn_in = read.number("compare_burn_in").value_or(c.burn_in);
  c.duration = read.number("compare_duration").value_or(c.duration);
  c.sample_interval = read.number("compare_sample_interval").value_or(c.sample_interval);
  c.max_seeds = static_cast<int>(read.integer("compare_seeds").value_or(c.max_seeds));
  c.margin_mean = read.number("compare_margin_mean").value_or(c.margin_mean);
  c.margin_coverage = read.number("compare_margin_coverage").value_or(c.margin_coverage);
  c.margin_spectrum = read.number("compare_margin_spectrum").value_or(c.margin_spectrum);
  c.margin_density = read.number("compare_margin_density").value_or(c.margin_density);
  c.margin_detail = read.number("compare_margin_detail").value_or(c.margin_detail);
  c.spectrum_bands = static_cast<int>(read.integer("compare_bands").value_or(c.spectrum_bands));
  c.eigenpairs = static_cast<int>(read.integer("compare_eigenpairs").value_or(c.eigenpairs));
  return c;
}

// A reaction-diffusion scene's run is its own time scale (a growth scene's reaction's too): by default the comparison discards the
// first half of the run (the pattern forming from its initial state) and averages the second half,
// sampled 20 times (enough samples that the time average is smooth, few enough that the snapshots'
// spectra cost little beside the run). Keys given in the file win.
void comparison_defaults_from_run_length(const json& j, Scene& scene) {
  ComparisonSettings& c = scene.comparison;
  std::optional<double> run_time = scene.sim_time;
  if (!run_time && scene.steps) run_time = static_cast<double>(*scene.steps) * scene.time_step;
  const bool burn_in_given = j.contains("compare_burn_in"), duration_given = j.contains("compare_duration");
  if (run_time) {
    if (!burn_in_given) c.burn_in = duration_given ? std::max(0.0, *run_time - c.duration) : 0.5 * *run_time;
    if (!duration_given) c.duration = std::max(scene.time_step, *run_time - c.burn_in);
  }
  if (!run_time && !(burn_in_given && duration_given)) {
    // No run length at all: the agent model's defaults are seconds of ITS dynamics and mean
    // nothing for a reaction's, so there is nothing to compare over (physarum compare says so;
    // physarum run takes --steps).
    c.burn_in = 0.0;
    c.duration = 0.0;
  }
  if (!j.contains("compare_sample_interval")) c.sample_interval = std::max(scene.time_step, c.duration / 20.0);
}

// The one place a scene's model is chosen: each model of SceneModel, from the last to the first,
// reads the scene if it is of that model; the first (the agent model) takes what no other claimed.
// The agent model's keys in a scene of another model are refused rather than silently ignored, so
// a half-converted scene does not run as something it is not.
template <size_t I = std::variant_size_v<SceneModel> - 1>
SceneModel read_model(const json& j, const std::string& path) {
  using Spec = std::variant_alternative_t<I, SceneModel>;
  std::optional<Spec> spec = read_model(ModelTag<Spec>{}, j, path);
  if constexpr (I > 0) {
    if (!spec) return read_model<I - 1>(j, path);
    for (const std::string& key : agent_model_keys())
      if (j.contains(key))
        throw InputError(path + ": key '" + key + "' belongs to the agent model (\"physarum\"), and this scene's " +
                         "\"model\" is \"" + model_key(*spec) + "\"");
  }
  return std::move(*spec);
}

}  // namespace

AgentModelSpec& Scene::agent_model() {
  if (auto* agents = std::get_if<AgentModelSpec>(&model)) return *agents;
  throw std::logic_error(scene_where(source) + ": the agent model's settings asked of a scene of another model");
}

const AgentModelSpec& Scene::agent_model() const { return const_cast<Scene&>(*this).agent_model(); }

Scene load_scene(const std::string& path, const nlohmann::json& overrides) {
  return scene_from_json(read_scene_file(path), path, overrides);
}

Scene scene_from_json(nlohmann::json j, const std::string& source, const nlohmann::json& overrides) {
  const std::string path = scene_where(source);  // for messages
  if (!j.is_object())
    throw InputError(path + ": a scene must be one JSON object ({...}), found " + std::string(j.type_name()));
  apply_scene_overrides(j, overrides, path);
  check_scene_nesting(j, path);
  hoist_growth_time_keys(j, path);
  refuse_unknown_keys(j, path);
  const std::filesystem::path folder = std::filesystem::path(source).parent_path();
  const SceneReader read{j, path};
  Scene scene;
  scene.source = source;

  // The keys every model shares.
  scene.mesh = read_mesh(read, path, folder);
  scene.scale_to_area = read.number("scale_to_area");
  scene.max_circumradius = read.number("max_circumradius");
  scene.min_angle_deg = read.number("min_angle").value_or(0.0);
  scene.time_step = *read.number("time_step");
  if (auto it = j.find("maps"); it != j.end()) {
    scene.maps = parse_maps(*it, folder.string(), path);
    scene.maps_given = *it;
  }
  if (auto seed = read.integer("seed")) scene.seed = static_cast<std::uint32_t>(*seed);
  scene.steps = read.integer("steps");
  scene.sim_time = read.number("sim_time");
  if (auto it = j.find("colormap"); it != j.end() && !it->is_null())
    scene.color_map = resolve_color_map(*it, folder.string(), path + ": key 'colormap'");
  scene.comparison = read_comparison(read);

  // The model's own keys.
  scene.model = read_model(j, path);
  // A model that runs on its own time scale (a reaction's) compares over its own run length.
  if (std::visit([](const auto& model) { return compares_over_its_run_length(model); }, scene.model))
    comparison_defaults_from_run_length(j, scene);

  // (A duration of 0 is no file's: compare_duration > 0. It is a reaction's scene without a run
  // length, which compare refuses saying so.)
  const ComparisonSettings& c = scene.comparison;
  if (c.sample_interval > c.duration && c.duration != 0.0)
    throw InputError(path + ": key 'compare_sample_interval' = " + std::to_string(c.sample_interval) +
                     " is longer than 'compare_duration' = " + std::to_string(c.duration) + " (no sample would be taken)");
  validate_scene(scene);
  return scene;
}

void validate_scene(const Scene& scene) {
  const std::string& s = scene.source;
  if (scene.mesh.empty()) throw InputError(scene_where(s) + ": key 'mesh' is empty (give a file path or shape:NAME)");
  if (scene.scale_to_area) check_range(s, "scale_to_area", *scene.scale_to_area);
  if (scene.max_circumradius) check_range(s, "max_circumradius", *scene.max_circumradius);
  check_range(s, "min_angle", scene.min_angle_deg);
  check_range(s, "time_step", scene.time_step);
  if (scene.steps) check_range(s, "steps", static_cast<double>(*scene.steps));
  if (scene.sim_time) check_range(s, "sim_time", *scene.sim_time);
  if (scene.steps && scene.sim_time)
    throw InputError(scene_where(s) + ": keys 'steps' and 'sim_time' are both given (give at most one run length)");
  std::visit([&](const auto& model) { validate_model(model, scene.maps, s); }, scene.model);
}

Scene reaction_diffusion_scene(const Scene& growth_scene) {
  if (!growth_scene.growth()) throw std::logic_error("reaction_diffusion_scene: not a growth scene");
  Scene scene = growth_scene;
  scene.model = growth_scene.growth()->reaction;
  return scene;
}

std::string model_key(const Scene& scene) {
  return std::visit([](const auto& model) { return model_key(model); }, scene.model);
}

nlohmann::ordered_json model_json(const Scene& scene) {
  return std::visit([&](const auto& model) { return model_json(model, scene); }, scene.model);
}

bool has_parameter_maps(const Scene& scene) {
  return is_agent_model(scene) && has_parameter_maps(scene.agent_model());
}

bool steady_mean_is_U(const Scene& scene) {
  return is_agent_model(scene) && steady_mean_is_U(scene.agent_model());
}

}  // namespace physarum
