#include "common/scene/scene_growth.hpp"

#include "common/base/errors.hpp"
#include "common/base/value_range.hpp"
#include "common/scene/scene_fields.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;

// Where the reaction–diffusion part's messages point: "scene.json: reaction_diffusion: key '...'".
std::string inner_source(const std::string& source) { return scene_where(source) + ": reaction_diffusion"; }

const json* given(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && !it->is_null() ? &*it : nullptr;
}

double positive_number(const json& v, const std::string& source, const std::string& key) {
  const double x = field_number(v, source, key);
  if (!(x > 0.0)) fail_key(source, key, ValueRange::number(x) + " must be > 0");
  return x;
}

long long whole_number(const json& v, const std::string& source, const std::string& key, long long lo, long long hi) {
  const double x = field_number(v, source, key);
  if (x != std::floor(x) || x < static_cast<double>(lo) || x > static_cast<double>(hi))
    fail_key(source, key, v.dump() + " must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<long long>(x);
}

bool boolean(const json& v, const std::string& source, const std::string& key) {
  if (!v.is_boolean()) fail_key(source, key, v.dump() + " must be true or false");
  return v.get<bool>();
}

ReactionDiffusionSpec read_reaction(const json& scene, const std::string& source) {
  json inner = json::object();
  if (const json* rd = given(scene, "reaction_diffusion")) {
    if (!rd->is_object()) fail_key(source, "reaction_diffusion", rd->dump() + " must be an object of reaction-diffusion keys");
    inner = *rd;
  }
  const std::string where = inner_source(source);
  for (auto it = inner.begin(); it != inner.end(); ++it) {
    const auto& keys = reaction_diffusion_keys();
    if (std::find(keys.begin(), keys.end(), it.key()) == keys.end() && it.key() != "integrator")
      fail_key(where, it.key(), "is not a reaction-diffusion key (model, parameters, parameter_noise, morphogens, "
                                "initial, reaction, dirichlet, preview_morphogen, integrator, time_step)");
  }
  if (!inner.contains("model") && !inner.contains("reaction")) inner["model"] = "gray-scott";
  if (inner.value("model", json()) == "growth" || inner.value("model", json()) == "physarum")
    fail_key(where, "model", inner["model"].dump() + " is not a reaction-diffusion model");
  if (scene.contains("integrator")) inner["integrator"] = scene["integrator"];
  std::optional<ReactionDiffusionSpec> spec = read_reaction_diffusion(inner, where);
  return std::move(*spec);
}

ShellSpec read_shell(const json& v, const std::string& source) {
  only_fields(v, {"thickness", "young_modulus", "poisson_ratio", "perturbation", "tolerance", "max_iterations"}, source, "shell");
  ShellSpec s;
  if (const json* x = given(v, "thickness")) s.material.thickness = field_number(*x, source, "shell.thickness");
  if (const json* x = given(v, "young_modulus")) s.material.young_modulus = field_number(*x, source, "shell.young_modulus");
  if (const json* x = given(v, "poisson_ratio")) s.material.poisson_ratio = field_number(*x, source, "shell.poisson_ratio");
  validate_shell_material(s.material, scene_where(source) + ": key 'shell'");
  if (const json* x = given(v, "perturbation")) {
    s.perturbation = field_number(*x, source, "shell.perturbation");
    if (!(s.perturbation >= 0.0 && s.perturbation <= 0.5))
      fail_key(source, "shell.perturbation", x->dump() + " must lie in [0, 0.5] (a fraction of the mean rest edge length)");
  }
  if (const json* x = given(v, "tolerance")) {
    s.newton.tolerance = positive_number(*x, source, "shell.tolerance");
    if (s.newton.tolerance >= 1e-2) fail_key(source, "shell.tolerance", x->dump() + " must be < 1e-2 (a residual strain)");
  }
  if (const json* x = given(v, "max_iterations"))
    s.newton.max_iterations = static_cast<int>(whole_number(*x, source, "shell.max_iterations", 1, 100000));
  return s;
}

GrowthRuleSpec read_rule(const json& v, const ReactionDiffusionSpec& reaction, const std::string& source) {
  only_fields(v, {"function", "m", "n", "gamma", "lambda", "rate", "a", "b", "stretch", "anisotropy"}, source, "growth");
  GrowthRuleSpec r;
  r.a = reaction.morphogens[0].name;
  r.b = reaction.morphogens[1].name;
  if (const json* s = given(v, "stretch")) {
    for (const char* law_field : {"function", "m", "n", "gamma", "lambda", "rate", "a", "b"})
      if (given(v, law_field))
        fail_key(source, std::string("growth.") + law_field,
                 "belongs to pattern-driven growth, and \"stretch\" prescribes the growth instead (give one of them)");
    r.stretch = field_operand(*s, source, "growth.stretch");
    if (const double* x = std::get_if<double>(&*r.stretch); x && !(*x > 0.0))
      fail_key(source, "growth.stretch", ValueRange::number(*x) + " must be > 0 (1 = no growth)");
  }
  if (const json* f = given(v, "function")) {
    if (*f == "polynomial") r.law.function = GrowthFunction::Polynomial;
    else if (*f == "exponential") r.law.function = GrowthFunction::Exponential;
    else fail_key(source, "growth.function", f->dump() + " must be \"polynomial\" (Eq. 7) or \"exponential\" (Eq. 6)");
  }
  if (const json* x = given(v, "m")) r.law.m = field_number(*x, source, "growth.m");
  if (const json* x = given(v, "n")) r.law.n = field_number(*x, source, "growth.n");
  if (const json* x = given(v, "gamma")) r.law.gamma = field_number(*x, source, "growth.gamma");
  if (const json* x = given(v, "lambda")) r.law.lambda = field_number(*x, source, "growth.lambda");
  if (const json* x = given(v, "rate")) r.law.rate = field_number(*x, source, "growth.rate");
  if (given(v, "lambda") && r.law.function != GrowthFunction::Exponential)
    fail_key(source, "growth.lambda", "is the exponential function's (Eq. 6); set \"function\": \"exponential\"");
  validate_growth_law(r.law, scene_where(source) + ": key 'growth'");
  for (auto [field, name] : {std::pair<const char*, std::string*>{"a", &r.a}, {"b", &r.b}})
    if (const json* x = given(v, field)) {
      *name = field_map_name(*x, source, std::string("growth.") + field);
      if (reaction.morphogen_index(*name) < 0)
        fail_key(source, std::string("growth.") + field, x->dump() + " is not a morphogen of the system");
    }
  if (const json* a = given(v, "anisotropy")) {
    only_fields(*a, {"direction", "across"}, source, "growth.anisotropy");
    GrowthAnisotropySpec spec;
    const json* d = given(*a, "direction");
    if (!d) fail_key(source, "growth.anisotropy", "missing \"direction\" (a vector map)");
    spec.direction = field_map_name(*d, source, "growth.anisotropy.direction");
    if (const json* x = given(*a, "across")) spec.across = field_number(*x, source, "growth.anisotropy.across");
    if (!(spec.across >= 0.0 && spec.across <= 10.0))
      fail_key(source, "growth.anisotropy.across", ValueRange::number(spec.across) +
                                                       " must lie in [0, 10] (growth across / growth along; 1 = isotropic)");
    r.anisotropy = spec;
  }
  return r;
}

GrowthSchedule read_schedule(const json& v, const std::string& source) {
  only_fields(v, {"reaction_steps", "growth_steps", "interleaved"}, source, "schedule");
  GrowthSchedule s;
  if (const json* x = given(v, "reaction_steps")) s.reaction_steps = whole_number(*x, source, "schedule.reaction_steps", 0, 1000000000LL);
  if (const json* x = given(v, "growth_steps")) s.growth_steps = static_cast<int>(whole_number(*x, source, "schedule.growth_steps", 1, 100000));
  if (const json* x = given(v, "interleaved")) s.interleaved = boolean(*x, source, "schedule.interleaved");
  return s;
}

}  // namespace

long long GrowthSchedule::total_steps() const {
  return interleaved ? static_cast<long long>(growth_steps) * (reaction_steps + 1) : reaction_steps + growth_steps;
}

bool GrowthSchedule::is_growth_step(long long s) const {
  return interleaved ? s % (reaction_steps + 1) == 0 : s > reaction_steps;
}

const std::vector<std::string>& growth_keys() {
  static const std::vector<std::string> keys = {"reaction_diffusion", "shell", "growth", "schedule", "refine", "dilute"};
  return keys;
}

void hoist_growth_time_keys(json& scene, const std::string& source) {
  if (scene.value("model", json()) != "growth") return;
  const auto rd = scene.find("reaction_diffusion");
  if (rd == scene.end() || !rd->is_object()) return;
  for (const char* key : {"time_step", "integrator"}) {
    if (!rd->contains(key)) continue;
    if (scene.contains(key))
      fail_key(source, key, "is given both at the top level and in 'reaction_diffusion' (give it once)");
    scene[key] = (*rd)[key];
    rd->erase(key);
  }
}

std::optional<GrowthSpec> read_growth(const json& j, const std::string& source) {
  if (j.value("model", json()) != "growth") {
    for (const std::string& key : growth_keys())
      if (given(j, key.c_str()))
        fail_key(source, key, "belongs to the growth model; set \"model\": \"growth\"");
    return std::nullopt;
  }
  for (const std::string& key : reaction_diffusion_keys())
    if (key != "model" && given(j, key.c_str()))
      fail_key(source, key, "belongs under \"reaction_diffusion\" in a growth scene");
  for (const char* key : {"steps", "sim_time"})
    if (given(j, key))
      fail_key(source, key, "a growth scene's length is its \"schedule\" (reaction_steps, growth_steps)");
  GrowthSpec spec;
  spec.reaction = read_reaction(j, source);
  if (const json* v = given(j, "shell")) spec.shell = read_shell(*v, source);
  if (const json* v = given(j, "growth")) spec.growth = read_rule(*v, spec.reaction, source);
  else spec.growth = read_rule(json::object(), spec.reaction, source);
  if (const json* v = given(j, "schedule")) spec.schedule = read_schedule(*v, source);
  if (const json* v = given(j, "refine")) {
    only_fields(*v, {"max_edge"}, source, "refine");
    if (const json* x = given(*v, "max_edge")) spec.max_edge = positive_number(*x, source, "refine.max_edge");
  }
  if (const json* v = given(j, "dilute")) spec.dilute = boolean(*v, source, "dilute");
  return spec;
}

void validate_growth(const GrowthSpec& spec, const MapSet& maps, const std::string& source) {
  validate_reaction_diffusion(spec.reaction, maps, inner_source(source));
  validate_shell_material(spec.shell.material, scene_where(source) + ": key 'shell'");
  validate_growth_law(spec.growth.law, scene_where(source) + ": key 'growth'");
  if (spec.growth.stretch)
    if (const auto* name = std::get_if<std::string>(&*spec.growth.stretch))
      check_map_reference(maps, source, "growth.stretch", *name, MapKind::Scalar);
  if (spec.growth.anisotropy)
    check_map_reference(maps, source, "growth.anisotropy.direction", spec.growth.anisotropy->direction, MapKind::Vector);
  if (spec.schedule.growth_steps < 1) fail_key(source, "schedule.growth_steps", "must be >= 1");
}

nlohmann::ordered_json growth_json(const GrowthSpec& spec) {
  nlohmann::ordered_json j;
  j["reaction_diffusion"] = reaction_diffusion_json(spec.reaction);
  const ShellMaterial& m = spec.shell.material;
  j["shell"] = {{"thickness", m.thickness}, {"young_modulus", m.young_modulus}, {"poisson_ratio", m.poisson_ratio},
                {"perturbation", spec.shell.perturbation}, {"tolerance", spec.shell.newton.tolerance},
                {"max_iterations", spec.shell.newton.max_iterations}};
  nlohmann::ordered_json g;
  if (spec.growth.stretch) {
    if (const double* x = std::get_if<double>(&*spec.growth.stretch)) g["stretch"] = *x;
    else g["stretch"] = std::get<std::string>(*spec.growth.stretch);
  } else {
    const GrowthLaw& law = spec.growth.law;
    g["function"] = law.function == GrowthFunction::Polynomial ? "polynomial" : "exponential";
    g["m"] = law.m, g["n"] = law.n, g["gamma"] = law.gamma;
    if (law.function == GrowthFunction::Exponential) g["lambda"] = law.lambda;
    g["a"] = spec.growth.a, g["b"] = spec.growth.b;
    g["rate"] = law.rate;
  }
  if (spec.growth.anisotropy)
    g["anisotropy"] = {{"direction", spec.growth.anisotropy->direction}, {"across", spec.growth.anisotropy->across}};
  j["growth"] = g;
  j["schedule"] = {{"reaction_steps", spec.schedule.reaction_steps}, {"growth_steps", spec.schedule.growth_steps},
                   {"interleaved", spec.schedule.interleaved}};
  if (spec.max_edge) j["refine"] = {{"max_edge", *spec.max_edge}};
  j["dilute"] = spec.dilute;
  return j;
}

}  // namespace physarum
