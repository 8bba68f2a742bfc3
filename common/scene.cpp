#include "common/scene.hpp"

#include "common/errors.hpp"
#include "common/scene_keys.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

namespace physarum {
namespace {

using nlohmann::json;

const SceneKey& spec_of(std::string_view name) {
  if (const SceneKey* k = find_scene_key(name)) return *k;
  throw std::logic_error("scene: no spec for key " + std::string(name));
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::string where(const std::string& source) { return source.empty() ? std::string("scene") : source; }

[[noreturn]] void fail_range(const std::string& source, std::string_view key, const std::string& shown_value,
                             const ValueRange& range) {
  throw InputError(where(source) + ": key '" + std::string(key) + "' = " + shown_value + " is out of range (" +
                   range.describe() + ")");
}

void check_range(const std::string& source, std::string_view key, double file_units_value) {
  const ValueRange& range = spec_of(key).range;
  if (!range.contains(file_units_value)) fail_range(source, key, ValueRange::number(file_units_value), range);
}

// ---- reading one value from the JSON object, with its type and range checked ----------------------

struct Reader {
  const json& object;
  const std::string& source;

  const json* find(std::string_view key) const {
    auto it = object.find(std::string(key));
    if (it == object.end()) {
      if (spec_of(key).required)
        throw InputError(where(source) + ": required key '" + std::string(key) + "' is missing");
      return nullptr;
    }
    return &*it;
  }

  [[noreturn]] void wrong_type(std::string_view key, const json& v, const char* expected) const {
    throw InputError(where(source) + ": key '" + std::string(key) + "' = " + v.dump() + " has the wrong type (" +
                     v.type_name() + "; expected " + expected + ")");
  }

  // A number, range-checked against the spec; returns nullopt when absent (optional keys) or null
  // (keys that allow it; null is treated as "not given" for optional keys too).
  std::optional<double> number(std::string_view key) const {
    const json* v = find(key);
    if (!v) return std::nullopt;
    const SceneKey& spec = spec_of(key);
    if (v->is_null() && (spec.kind == KeyKind::NumberOrNull || !spec.required)) return std::nullopt;
    if (!v->is_number())
      wrong_type(key, *v, spec.kind == KeyKind::NumberOrNull ? "a number or null" : "a number");
    const double x = v->get<double>();
    if (!spec.range.contains(x)) fail_range(source, key, v->dump(), spec.range);
    return x;
  }

  // An integer; a float with an integral value (1e5) is accepted, 2.5 is not.
  std::optional<long long> integer(std::string_view key) const {
    const json* v = find(key);
    if (!v) return std::nullopt;
    const SceneKey& spec = spec_of(key);
    if (v->is_null() && !spec.required) return std::nullopt;
    if (!v->is_number()) wrong_type(key, *v, "an integer");
    const double x = v->get<double>();
    if (!spec.range.contains(x)) fail_range(source, key, v->dump(), spec.range);
    if (v->is_number_float() && x != std::floor(x))
      throw InputError(where(source) + ": key '" + std::string(key) + "' = " + v->dump() +
                       " must be a whole number (" + spec.range.describe() + ")");
    return v->is_number_unsigned() ? static_cast<long long>(v->get<unsigned long long>())
           : v->is_number_integer() ? v->get<long long>()
                                    : static_cast<long long>(x);
  }

  std::optional<std::string> string(std::string_view key) const {
    const json* v = find(key);
    if (!v) return std::nullopt;
    if (v->is_null() && !spec_of(key).required) return std::nullopt;
    if (!v->is_string()) wrong_type(key, *v, "a string");
    return v->get<std::string>();
  }
};

json parse_scene_text(const std::string& text, const std::string& path) {
  // Duplicate keys are a likely copy-paste mistake and nlohmann silently keeps the last one, so the
  // parser callback watches the keys of the top-level object.
  std::set<std::string> seen;
  std::string duplicate;
  int depth = 0;
  auto callback = [&](int /*callback_depth*/, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) ++depth;
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

}  // namespace

Scene load_scene(const std::string& path, const nlohmann::json& overrides) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the scene file");
  std::stringstream buffer;
  buffer << file.rdbuf();
  if (file.bad()) throw InputError(path + ": cannot read the scene file");
  json j = parse_scene_text(buffer.str(), path);
  if (!overrides.is_object()) throw InputError(path + ": scene overrides must be a JSON object");
  for (auto it = overrides.begin(); it != overrides.end(); ++it) j[it.key()] = it.value();

  for (auto it = j.begin(); it != j.end(); ++it) {
    if (!find_scene_key(it.key()))
      throw InputError(path + ": unknown key '" + it.key() + "' (did you mean '" + closest_scene_key(it.key()) +
                       "'?)");
  }

  const Reader read{j, path};
  Scene scene;
  scene.source = path;

  const std::string mesh = *read.string("mesh");
  if (mesh.empty()) throw InputError(path + ": key 'mesh' = \"\" is empty (give a file path or shape:NAME)");
  if (mesh.rfind("shape:", 0) == 0) {
    scene.mesh = mesh;
  } else {
    std::filesystem::path mesh_path(mesh);
    if (mesh_path.is_relative()) mesh_path = std::filesystem::path(path).parent_path() / mesh_path;
    mesh_path = mesh_path.lexically_normal();
    if (!std::filesystem::exists(mesh_path))
      throw InputError(path + ": key 'mesh' = \"" + mesh + "\": file not found (looked for " + mesh_path.string() +
                       ")");
    scene.mesh = mesh_path.string();
  }

  scene.scale_to_area = read.number("scale_to_area");
  scene.max_circumradius = read.number("max_circumradius");
  scene.min_angle_deg = read.number("min_angle").value_or(0.0);

  scene.agents = static_cast<int>(*read.integer("agents"));
  scene.time_step = *read.number("time_step");
  for (const ParameterSpec& p : kParameterTable) {
    // Absent: the default (optional keys only); null: +infinity (keys that allow it).
    const std::optional<double> file_value = read.number(p.key);
    const double value = file_value ? *file_value : p.default_value.value_or(kInfinity);
    scene.parameters[p.id] = value * p.file_to_si;
  }

  if (auto integrator = read.string("integrator")) {
    if (*integrator == "forward") scene.integrator = Integrator::ForwardEuler;
    else if (*integrator == "backward") scene.integrator = Integrator::BackwardEuler;
    else
      throw InputError(path + ": key 'integrator' = \"" + *integrator +
                       "\" is out of range (must be \"forward\" or \"backward\")");
  }
  if (auto seed = read.integer("seed")) scene.seed = static_cast<std::uint32_t>(*seed);
  scene.steps = read.integer("steps");
  scene.sim_time = read.number("sim_time");

  if (auto it = j.find("colormap"); it != j.end() && !it->is_null())
    scene.colormap = resolve_color_map(*it, std::filesystem::path(path).parent_path().string(), path + ": key 'colormap'");

  ComparisonSettings& c = scene.comparison;
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
  if (c.sample_interval > c.duration)
    throw InputError(path + ": key 'compare_sample_interval' = " + std::to_string(c.sample_interval) +
                     " is longer than 'compare_duration' = " + std::to_string(c.duration) + " (no sample would be taken)");

  validate_scene(scene);
  return scene;
}

void validate_scene(const Scene& scene) {
  const std::string& s = scene.source;
  if (scene.mesh.empty()) throw InputError(where(s) + ": key 'mesh' is empty (give a file path or shape:NAME)");
  if (scene.scale_to_area) check_range(s, "scale_to_area", *scene.scale_to_area);
  if (scene.max_circumradius) check_range(s, "max_circumradius", *scene.max_circumradius);
  check_range(s, "min_angle", scene.min_angle_deg);
  check_range(s, "agents", scene.agents);
  check_range(s, "time_step", scene.time_step);
  for (const ParameterSpec& p : kParameterTable) {
    const double value = scene.parameters[p.id];
    if (p.null_means_infinite && value == kInfinity) continue;
    check_range(s, p.key, value / p.file_to_si);
  }
  if (scene.steps) check_range(s, "steps", static_cast<double>(*scene.steps));
  if (scene.sim_time) check_range(s, "sim_time", *scene.sim_time);
  if (scene.steps && scene.sim_time)
    throw InputError(where(s) + ": keys 'steps' and 'sim_time' are both given (give at most one run length)");
}

}  // namespace physarum
