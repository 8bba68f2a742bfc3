#include "common/scene.hpp"

#include "common/errors.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

namespace physarum {
namespace {

using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDegree = std::numbers::pi / 180.0;

// An interval of allowed values, in the units of the scene FILE (degrees for angles), so one table
// serves both the file checks and the checks of a scene built in code.
struct Range {
  double low = -kInf;
  bool low_open = false;  // true: value must be > low; false: >= low
  double high = kInf;
  bool high_open = false;

  bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (low_open ? !(v > low) : !(v >= low)) return false;
    if (high_open ? !(v < high) : !(v <= high)) return false;
    return true;
  }
  std::string describe() const {
    auto num = [](double x) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.10g", x);
      return std::string(buf);
    };
    const bool has_low = std::isfinite(low), has_high = std::isfinite(high);
    if (has_low && has_high)
      return "must be in " + std::string(low_open ? "(" : "[") + num(low) + ", " + num(high) + (high_open ? ")" : "]");
    if (has_low) return "must be " + std::string(low_open ? "> " : ">= ") + num(low);
    if (has_high) return "must be " + std::string(high_open ? "< " : "<= ") + num(high);
    return "must be a finite number";
  }
};

constexpr Range positive{0.0, true};
constexpr Range non_negative{0.0, false};

enum class Kind { Number, Integer, String, NumberOrNull };

struct KeySpec {
  std::string_view name;
  Kind kind;
  bool required;
  Range range;
};

// Every key a scene file may contain. Required keys are the surface and the parameters of Table 1
// whose value changes the pattern; a missing one is an error rather than a silent default.
// mean_lifetime is required too, but may be null (no turnover), so "no turnover" is always a choice.
const std::vector<KeySpec>& key_specs() {
  static const std::vector<KeySpec> specs = {
      {"mesh", Kind::String, true, {}},
      {"scale_to_area", Kind::Number, false, positive},
      {"max_circumradius", Kind::Number, false, positive},
      {"min_angle", Kind::Number, false, Range{0.0, false, 30.0, false}},  // refinement terminates up to ~30 deg
      {"agents", Kind::Integer, true, Range{1.0, false, 2147483647.0, false}},
      {"time_step", Kind::Number, true, positive},
      {"sensor_distance", Kind::Number, true, positive},
      {"sensor_angle", Kind::Number, true, Range{-180.0, false, 180.0, false}},  // negative = repulsion
      {"move_rate", Kind::Number, true, non_negative},
      {"turn_rate", Kind::Number, true, non_negative},
      {"turn_frequency", Kind::Number, true, positive},
      {"deposit_rate", Kind::Number, true, non_negative},
      // r_dec > 0: the steady state (U, Eq. 5) divides by it; without decay the pheromone grows forever.
      {"decay_rate", Kind::Number, true, positive},
      {"diffuse_rate", Kind::Number, true, non_negative},
      {"mean_lifetime", Kind::NumberOrNull, true, positive},
      {"activation_time", Kind::Number, false, non_negative},
      {"integrator", Kind::String, false, {}},
      {"seed", Kind::Integer, false, Range{0.0, false, 4294967295.0, false}},
      {"steps", Kind::Integer, false, Range{1.0, false, 1.0e15, false}},
      {"sim_time", Kind::Number, false, positive},
      // ---- the differential harness (ComparisonSettings) ----
      {"compare_burn_in", Kind::Number, false, non_negative},
      {"compare_duration", Kind::Number, false, positive},
      {"compare_sample_interval", Kind::Number, false, positive},
      {"compare_seeds", Kind::Integer, false, Range{2.0, false, 10000.0, false}},
      {"compare_margin_mean", Kind::Number, false, positive},
      {"compare_margin_coverage", Kind::Number, false, positive},
      {"compare_margin_spectrum", Kind::Number, false, positive},
      {"compare_margin_density", Kind::Number, false, positive},
      {"compare_margin_detail", Kind::Number, false, positive},
      {"compare_bands", Kind::Integer, false, Range{1.0, false, 64.0, false}},
      {"compare_eigenpairs", Kind::Integer, false, Range{4.0, false, 2000.0, false}},
  };
  return specs;
}

const KeySpec& spec_of(std::string_view name) {
  for (const KeySpec& s : key_specs())
    if (s.name == name) return s;
  throw std::logic_error("scene: no spec for key " + std::string(name));
}

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The known key a typo most likely meant: one that contains the name (or is contained in it, as
// "decay" in "decay_rate"), otherwise the one at the smallest edit distance.
std::string closest_key(std::string_view name) {
  for (const KeySpec& s : key_specs())
    if (name.size() >= 3 && (s.name.find(name) != std::string_view::npos || name.find(s.name) != std::string_view::npos))
      return std::string(s.name);
  std::string best;
  size_t best_distance = std::numeric_limits<size_t>::max();
  for (const KeySpec& s : key_specs()) {
    const size_t d = edit_distance(name, s.name);
    if (d < best_distance) best_distance = d, best = std::string(s.name);
  }
  return best;
}

std::string format_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string where(const std::string& source) { return source.empty() ? std::string("scene") : source; }

[[noreturn]] void fail_range(const std::string& source, std::string_view key, const std::string& shown_value,
                             const Range& range) {
  throw InputError(where(source) + ": key '" + std::string(key) + "' = " + shown_value + " is out of range (" +
                   range.describe() + ")");
}

void check_range(const std::string& source, std::string_view key, double file_units_value) {
  const Range& range = spec_of(key).range;
  if (!range.contains(file_units_value)) fail_range(source, key, format_number(file_units_value), range);
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
    const KeySpec& spec = spec_of(key);
    if (v->is_null() && (spec.kind == Kind::NumberOrNull || !spec.required)) return std::nullopt;
    if (!v->is_number())
      wrong_type(key, *v, spec.kind == Kind::NumberOrNull ? "a number or null" : "a number");
    const double x = v->get<double>();
    if (!spec.range.contains(x)) fail_range(source, key, v->dump(), spec.range);
    return x;
  }

  // An integer; a float with an integral value (1e5) is accepted, 2.5 is not.
  std::optional<long long> integer(std::string_view key) const {
    const json* v = find(key);
    if (!v) return std::nullopt;
    const KeySpec& spec = spec_of(key);
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

Scene load_scene(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the scene file");
  std::stringstream buffer;
  buffer << file.rdbuf();
  if (file.bad()) throw InputError(path + ": cannot read the scene file");
  const json j = parse_scene_text(buffer.str(), path);

  for (auto it = j.begin(); it != j.end(); ++it) {
    const bool known = std::any_of(key_specs().begin(), key_specs().end(),
                                   [&](const KeySpec& s) { return s.name == it.key(); });
    if (!known)
      throw InputError(path + ": unknown key '" + it.key() + "' (did you mean '" + closest_key(it.key()) + "'?)");
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
  scene.sensor_distance = *read.number("sensor_distance");
  scene.sensor_angle = *read.number("sensor_angle") * kDegree;
  scene.move_rate = *read.number("move_rate");
  scene.turn_rate = *read.number("turn_rate") * kDegree;
  scene.turn_frequency = *read.number("turn_frequency");
  scene.deposit_rate = *read.number("deposit_rate");
  scene.decay_rate = *read.number("decay_rate");
  scene.diffuse_rate = *read.number("diffuse_rate");
  scene.mean_lifetime = read.number("mean_lifetime");
  scene.activation_time = read.number("activation_time").value_or(0.0);

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

  ComparisonSettings& c = scene.comparison;
  c.burn_in = read.number("compare_burn_in").value_or(c.burn_in);
  c.duration = read.number("compare_duration").value_or(c.duration);
  c.sample_interval = read.number("compare_sample_interval").value_or(c.sample_interval);
  c.seeds = static_cast<int>(read.integer("compare_seeds").value_or(c.seeds));
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
  check_range(s, "sensor_distance", scene.sensor_distance);
  check_range(s, "sensor_angle", scene.sensor_angle / kDegree);
  check_range(s, "move_rate", scene.move_rate);
  check_range(s, "turn_rate", scene.turn_rate / kDegree);
  check_range(s, "turn_frequency", scene.turn_frequency);
  check_range(s, "deposit_rate", scene.deposit_rate);
  check_range(s, "decay_rate", scene.decay_rate);
  check_range(s, "diffuse_rate", scene.diffuse_rate);
  if (scene.mean_lifetime) check_range(s, "mean_lifetime", *scene.mean_lifetime);
  check_range(s, "activation_time", scene.activation_time);
  if (scene.steps) check_range(s, "steps", static_cast<double>(*scene.steps));
  if (scene.sim_time) check_range(s, "sim_time", *scene.sim_time);
  if (scene.steps && scene.sim_time)
    throw InputError(where(s) + ": keys 'steps' and 'sim_time' are both given (give at most one run length)");
}

}  // namespace physarum
