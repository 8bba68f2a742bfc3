#include "common/scene/scene_reaction_diffusion.hpp"

#include "common/scene/scene_fields.hpp"
#include "common/base/errors.hpp"
#include "common/reaction_diffusion/reaction_formula.hpp"
#include "common/reaction_diffusion/reaction_models.hpp"
#include "common/base/value_range.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;

constexpr size_t kMinMorphogens = 2;

std::string number_text(double x) { return ValueRange::number(x); }


// "integrator": a reaction-diffusion system steps explicitly (with automatic sub-steps) or IMEX.
Integrator read_reaction_integrator(const json& j, const std::string& source) {
  const auto integrator = SceneReader{j, source}.string("integrator");
  if (!integrator || *integrator == "forward") return Integrator::Forward;
  if (*integrator == "imex") return Integrator::Imex;
  throw InputError(source + ": key 'integrator' = \"" + *integrator +
                   "\" is out of range (a reaction-diffusion model takes \"forward\" (explicit, automatic "
                   "sub-steps) or \"imex\" (implicit diffusion, explicit reaction))");
}

// A name a formula can use: a letter or '_' first, then letters, digits, '_'; not a function.
void check_identifier(const std::string& name, const std::string& source, const std::string& key) {
  const bool ok = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                  std::all_of(name.begin(), name.end(),
                              [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  if (!ok) fail_key(source, key, "'" + name + "' is not a name a formula can use (letters, digits and _, not a digit first)");
  const auto& functions = reaction_formula_functions();
  if (std::find(functions.begin(), functions.end(), name) != functions.end())
    fail_key(source, key, "'" + name + "' is the name of a function");
}

// A morphogen is written as a vertex property of the run's PLY files (common/output/ply_writer.cpp),
// which cannot take the names of the vertices' own properties: refused here, before the run, and
// not when the finished run is written.
void check_writable_morphogen(const std::string& name, const std::string& source, const std::string& key) {
  for (const char* taken : {"x", "y", "z", "red", "green", "blue"})
    if (name == taken)
      fail_key(source, key, "'" + name + "' is a vertex property of the PLY files a run writes (x, y, z, red, green, "
                            "blue): give the morphogen another name");
}

std::string morphogen_list(const std::vector<MorphogenSpec>& morphogens) {
  std::string list;
  for (const MorphogenSpec& m : morphogens) list += (list.empty() ? "" : ", ") + m.name;
  return list;
}

MorphogenValues read_values(const json& v, const std::vector<MorphogenSpec>& morphogens, const std::string& source,
                            const std::string& key) {
  if (!v.is_object()) fail_key(source, key, v.dump() + " must be an object {MORPHOGEN: value, ...}");
  MorphogenValues values;
  for (auto it = v.begin(); it != v.end(); ++it) {
    const std::string entry = key + "." + it.key();
    if (std::none_of(morphogens.begin(), morphogens.end(), [&](const MorphogenSpec& m) { return m.name == it.key(); }))
      fail_key(source, entry, "no morphogen of that name (the morphogens: " + morphogen_list(morphogens) + ")");
    values.emplace_back(it.key(), field_number(*it, source, entry));
  }
  return values;
}

std::vector<std::string> formula_names(const ReactionDiffusionSpec& spec) {
  std::vector<std::string> names;
  for (const MorphogenSpec& m : spec.morphogens) names.push_back(m.name);
  for (const auto& [name, value] : spec.coefficients) names.push_back(name);
  return names;
}

void read_morphogen_entry(const json& entry, MorphogenSpec& m, bool diffusion_required, const std::string& source,
                          const std::string& key) {
  only_fields(entry, {"diffusion", "initial", "anisotropy", "minimum"}, source, key);
  if (const auto d = entry.find("diffusion"); d != entry.end())
    m.diffusion = field_operand(*d, source, key + ".diffusion");
  else if (diffusion_required)
    fail_key(source, key, "missing \"diffusion\" (m^2/s: a number >= 0 or a scalar map name)");
  if (const auto i = entry.find("initial"); i != entry.end()) m.initial = field_operand(*i, source, key + ".initial");
  if (const auto floor = entry.find("minimum"); floor != entry.end())
    m.minimum = floor->is_null() ? -std::numeric_limits<double>::infinity() : field_number(*floor, source, key + ".minimum");
  if (const auto a = entry.find("anisotropy"); a != entry.end() && !a->is_null()) {
    const std::string akey = key + ".anisotropy";
    only_fields(*a, {"direction", "ratio"}, source, akey);
    AnisotropySpec spec;
    const auto dir = a->find("direction");
    if (dir == a->end()) fail_key(source, akey, "missing \"direction\" (a vector map)");
    spec.direction = field_map_name(*dir, source, akey + ".direction");
    const auto ratio = a->find("ratio");
    if (ratio == a->end()) fail_key(source, akey, "missing \"ratio\" (rate across the direction / rate along it, > 0)");
    spec.ratio = field_operand(*ratio, source, akey + ".ratio");
    m.anisotropy = spec;
  }
}

}  // namespace

int ReactionDiffusionSpec::morphogen_index(const std::string& name) const {
  for (size_t i = 0; i < morphogens.size(); ++i)
    if (morphogens[i].name == name) return static_cast<int>(i);
  return -1;
}

const std::vector<std::string>& reaction_diffusion_keys() {
  static const std::vector<std::string> keys = {"model",     "parameters", "parameter_noise",  "morphogens",
                                                "initial",   "reaction",   "dirichlet",        "preview_morphogen"};
  return keys;
}

namespace {

// A key of the scene object, nullptr when absent or null.
const json* given_key(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && !it->is_null() ? &*it : nullptr;
}

// "model" (and "reaction", which implies "custom"); "physarum" for the agent model, whose scenes
// may not carry the reaction-diffusion keys.
std::string read_model_name(const json& j, const std::string& source) {
  std::string model = "physarum";
  if (const json* m = given_key(j, "model")) {
    if (!m->is_string()) fail_key(source, "model", m->dump() + " must be a string");
    model = m->get<std::string>();
  }
  const json* reaction = given_key(j, "reaction");
  if (model == "physarum" && reaction) model = "custom";
  if (model == "physarum") {
    for (const std::string& key : reaction_diffusion_keys())
      if (key != "model" && given_key(j, key.c_str()))
        fail_key(source, key, "belongs to a reaction-diffusion model, and this scene's \"model\" is \"physarum\" "
                          "(the default; set \"model\" to one of " + reaction_model_names() + ", or give \"reaction\")");
  } else if (model == "custom") {
    if (!reaction) fail_key(source, "model", "\"custom\" needs \"reaction\": {MORPHOGEN: FORMULA, ...}");
  } else if (!find_reaction_model(model)) {
    fail_key(source, "model", "\"" + model + "\" is not a model (physarum, " + reaction_model_names() + ", or custom)");
  } else if (reaction) {
    fail_key(source, "reaction", "custom kinetics, and \"model\" names the built-in \"" + model +
                                 "\" (leave \"model\" out or set it to \"custom\")");
  }
  return model;
}

// A named model's morphogens, kinetics and default coefficients.
void take_named_model(const ReactionModel& named, ReactionDiffusionSpec& spec) {
  for (size_t i = 0; i < named.morphogens.size(); ++i) {
    MorphogenSpec m;
    m.name = named.morphogens[i];
    m.diffusion = named.diffusion[i];
    m.initial = named.initial[i];
    m.minimum = named.minimum[i];
    spec.morphogens.push_back(m);
  }
  spec.reaction = named.reaction;
  for (const auto& [name, value] : named.coefficients) spec.coefficients.emplace_back(name, value);
  spec.parameter_noise = named.parameter_noise;
}

// "reaction": custom kinetics, one formula per morphogen (which then each need a "morphogens" entry).
void read_custom_kinetics(const json& reaction, const json* morphogens, ReactionDiffusionSpec& spec,
                          const std::string& source) {
  if (!reaction.is_object()) fail_key(source, "reaction", reaction.dump() + " must be an object {MORPHOGEN: FORMULA, ...}");
  if (reaction.size() < kMinMorphogens || reaction.size() > static_cast<size_t>(kMaxMorphogens))
    fail_key(source, "reaction", "has " + std::to_string(reaction.size()) + " morphogens; a system has 2 to " + std::to_string(kMaxMorphogens));
  for (auto it = reaction.begin(); it != reaction.end(); ++it) {
    const std::string key = "reaction." + it.key();
    check_identifier(it.key(), source, key);
    check_writable_morphogen(it.key(), source, key);
    if (!it->is_string()) fail_key(source, key, it->dump() + " must be a formula (a string)");
    MorphogenSpec m;
    m.name = it.key();
    spec.morphogens.push_back(m);
    spec.reaction.push_back(it->get<std::string>());
  }
  if (!morphogens) fail_key(source, "morphogens", "missing: custom kinetics need each morphogen's \"diffusion\"");
  for (const MorphogenSpec& m : spec.morphogens)
    if (!morphogens->contains(m.name))
      fail_key(source, "morphogens", "missing an entry for \"" + m.name + "\" (its \"diffusion\" is required)");
}

// "morphogens": each entry overrides (named model) or gives (custom) one morphogen's settings.
void read_morphogens(const json& morphogens, bool named, ReactionDiffusionSpec& spec, const std::string& source) {
  for (auto it = morphogens.begin(); it != morphogens.end(); ++it) {
    const int index = spec.morphogen_index(it.key());
    if (index < 0)
      fail_key(source, "morphogens." + it.key(), "no morphogen of that name (the morphogens: " +
                                                 morphogen_list(spec.morphogens) + ")");
    read_morphogen_entry(*it, spec.morphogens[static_cast<size_t>(index)], !named, source, "morphogens." + it.key());
  }
}

// "parameters": a named model's coefficients replaced (no new ones), a custom model's given.
void read_coefficients(const json& p, const ReactionModel* named, ReactionDiffusionSpec& spec, const std::string& source) {
  if (!p.is_object()) fail_key(source, "parameters", p.dump() + " must be an object {NAME: number or map, ...}");
  for (auto it = p.begin(); it != p.end(); ++it) {
    const std::string key = "parameters." + it.key();
    check_identifier(it.key(), source, key);
    if (spec.morphogen_index(it.key()) >= 0) fail_key(source, key, "'" + it.key() + "' is a morphogen, not a coefficient");
    const MapOperand value = field_operand(*it, source, key);
    auto existing = std::find_if(spec.coefficients.begin(), spec.coefficients.end(),
                                 [&](const auto& c) { return c.first == it.key(); });
    if (existing != spec.coefficients.end()) {
      existing->second = value;
    } else if (named) {
      std::string known;
      for (const auto& c : named->coefficients) known += (known.empty() ? "" : ", ") + c.first;
      fail_key(source, key, "\"" + spec.model + "\" has no coefficient '" + it.key() + "' (it has " + known + ")");
    } else {
      spec.coefficients.emplace_back(it.key(), value);
    }
  }
}

// "parameter_noise": {COEFFICIENT: amplitude}, replacing a named model's default for that coefficient.
void read_parameter_noise(const json& p, ReactionDiffusionSpec& spec, const std::string& source) {
  if (!p.is_object()) fail_key(source, "parameter_noise", p.dump() + " must be an object {COEFFICIENT: amplitude >= 0, ...}");
  for (auto it = p.begin(); it != p.end(); ++it) {
    const std::string key = "parameter_noise." + it.key();
    if (std::none_of(spec.coefficients.begin(), spec.coefficients.end(), [&](const auto& c) { return c.first == it.key(); })) {
      std::string known;
      for (const auto& c : spec.coefficients) known += (known.empty() ? "" : ", ") + c.first;
      fail_key(source, key, "no coefficient of that name (the coefficients: " + known + ")");
    }
    const double amplitude = field_number(*it, source, key);
    auto existing = std::find_if(spec.parameter_noise.begin(), spec.parameter_noise.end(),
                                 [&](const auto& n) { return n.first == it.key(); });
    if (existing != spec.parameter_noise.end()) existing->second = amplitude;
    else spec.parameter_noise.emplace_back(it.key(), amplitude);
  }
}

// "initial": noise, a seeded region, spots.
ReactionInitialSpec read_initial(const json& init, const std::vector<MorphogenSpec>& morphogens, const std::string& source) {
  ReactionInitialSpec initial;
  only_fields(init, {"noise", "seed_region", "spots"}, source, "initial");
  if (const auto n = init.find("noise"); n != init.end()) initial.noise = field_number(*n, source, "initial.noise");
  if (const auto r = init.find("seed_region"); r != init.end() && !r->is_null()) {
    only_fields(*r, {"map", "values"}, source, "initial.seed_region");
    SeedRegionSpec seed;
    if (!r->contains("map")) fail_key(source, "initial.seed_region", "missing \"map\" (a scalar map, 0..1)");
    seed.map = field_map_name(r->at("map"), source, "initial.seed_region.map");
    if (!r->contains("values")) fail_key(source, "initial.seed_region", "missing \"values\" ({MORPHOGEN: value})");
    seed.values = read_values(r->at("values"), morphogens, source, "initial.seed_region.values");
    initial.seed_region = seed;
  }
  if (const auto s = init.find("spots"); s != init.end() && !s->is_null()) {
    only_fields(*s, {"count", "radius", "values"}, source, "initial.spots");
    SpotsSpec spots;
    for (const char* f : {"count", "radius", "values"})
      if (!s->contains(f)) fail_key(source, "initial.spots", std::string("missing \"") + f + "\"");
    const double count = field_number(s->at("count"), source, "initial.spots.count");
    if (count < 1 || count != std::floor(count) || count > 1e7)
      fail_key(source, "initial.spots.count", number_text(count) + " must be a whole number 1..1e7");
    spots.count = static_cast<int>(count);
    spots.radius = field_number(s->at("radius"), source, "initial.spots.radius");
    spots.values = read_values(s->at("values"), morphogens, source, "initial.spots.values");
    initial.spots = spots;
  }
  return initial;
}

DirichletSpec read_dirichlet(const json& d, const std::vector<MorphogenSpec>& morphogens, const std::string& source) {
  only_fields(d, {"map", "values"}, source, "dirichlet");
  DirichletSpec dirichlet;
  if (!d.contains("map")) fail_key(source, "dirichlet", "missing \"map\" (a scalar map: fixed where >= 0.5)");
  dirichlet.map = field_map_name(d.at("map"), source, "dirichlet.map");
  if (d.contains("values")) dirichlet.values = read_values(d.at("values"), morphogens, source, "dirichlet.values");
  return dirichlet;
}

}  // namespace

std::optional<ReactionDiffusionSpec> read_reaction_diffusion(const json& j, const std::string& source) {
  const std::string model = read_model_name(j, source);
  if (model == "physarum") return std::nullopt;
  ReactionDiffusionSpec spec;
  spec.model = model;
  const ReactionModel* named = find_reaction_model(model);
  const json* morphogens = given_key(j, "morphogens");
  if (morphogens && !morphogens->is_object())
    fail_key(source, "morphogens", morphogens->dump() + " must be an object {NAME: {\"diffusion\", \"initial\", \"anisotropy\", \"minimum\"}}");
  if (named) take_named_model(*named, spec);
  else read_custom_kinetics(*given_key(j, "reaction"), morphogens, spec, source);
  if (morphogens) read_morphogens(*morphogens, named != nullptr, spec, source);
  if (const json* p = given_key(j, "parameters")) read_coefficients(*p, named, spec, source);
  if (const json* p = given_key(j, "parameter_noise")) read_parameter_noise(*p, spec, source);
  if (const json* init = given_key(j, "initial")) spec.initial = read_initial(*init, spec.morphogens, source);
  if (const json* d = given_key(j, "dirichlet")) spec.dirichlet = read_dirichlet(*d, spec.morphogens, source);
  spec.preview_morphogen = spec.morphogens[1].name;
  if (const json* p = given_key(j, "preview_morphogen")) {
    if (!p->is_string() || spec.morphogen_index(p->get<std::string>()) < 0)
      fail_key(source, "preview_morphogen", p->dump() + " must be a morphogen's name (" + morphogen_list(spec.morphogens) + ")");
    spec.preview_morphogen = p->get<std::string>();
  }
  spec.integrator = read_reaction_integrator(j, source);
  return spec;
}

void validate_reaction_diffusion(const ReactionDiffusionSpec& spec, const MapSet& maps, const std::string& source) {
  auto check_map = [&](const std::string& key, const std::string& name, MapKind kind) {
    check_map_reference(maps, source, key, name, kind);
  };
  if (spec.morphogens.size() < kMinMorphogens || spec.morphogens.size() > static_cast<size_t>(kMaxMorphogens))
    fail_key(source, "morphogens", std::to_string(spec.morphogens.size()) + " morphogens; a system has 2 to " + std::to_string(kMaxMorphogens));
  if (spec.reaction.size() != spec.morphogens.size())
    fail_key(source, "reaction", "one formula per morphogen is needed");
  for (const MorphogenSpec& m : spec.morphogens) {
    const std::string key = "morphogens." + m.name;
    if (const auto* rate = std::get_if<double>(&m.diffusion)) {
      if (!(*rate >= 0.0) || !std::isfinite(*rate))
        fail_key(source, key + ".diffusion", number_text(*rate) + " m^2/s must be >= 0");
    } else {
      check_map(key + ".diffusion", std::get<std::string>(m.diffusion), MapKind::Scalar);
    }
    if (const auto* map = std::get_if<std::string>(&m.initial)) check_map(key + ".initial", *map, MapKind::Scalar);
    if (m.anisotropy) {
      check_map(key + ".anisotropy.direction", m.anisotropy->direction, MapKind::Vector);
      if (const double* ratio = std::get_if<double>(&m.anisotropy->ratio)) {
        if (!(*ratio > 0.0) || !std::isfinite(*ratio)) fail_key(source, key + ".anisotropy.ratio", number_text(*ratio) + " must be > 0");
      } else {
        check_map(key + ".anisotropy.ratio", std::get<std::string>(m.anisotropy->ratio), MapKind::Scalar);
      }
    }
  }
  for (const auto& [name, value] : spec.coefficients)
    if (const auto* map = std::get_if<std::string>(&value)) check_map("parameters." + name, *map, MapKind::Scalar);
  for (const auto& [name, amplitude] : spec.parameter_noise)
    if (!(amplitude >= 0.0) || !std::isfinite(amplitude))
      fail_key(source, "parameter_noise." + name, number_text(amplitude) + " must be >= 0");
  const std::vector<std::string> names = formula_names(spec);
  for (size_t m = 0; m < spec.reaction.size(); ++m)
    ReactionFormula(spec.reaction[m], names, scene_where(source) + ": key 'reaction." + spec.morphogens[m].name + "'");
  if (!(spec.initial.noise >= 0.0)) fail_key(source, "initial.noise", number_text(spec.initial.noise) + " must be >= 0");
  if (spec.initial.seed_region) check_map("initial.seed_region.map", spec.initial.seed_region->map, MapKind::Scalar);
  if (spec.initial.spots) {
    if (spec.initial.spots->count < 1) fail_key(source, "initial.spots.count", "must be >= 1");
    if (!(spec.initial.spots->radius > 0.0))
      fail_key(source, "initial.spots.radius", number_text(spec.initial.spots->radius) + " m must be > 0");
  }
  if (spec.dirichlet) check_map("dirichlet.map", spec.dirichlet->map, MapKind::Scalar);
  if (spec.morphogen_index(spec.preview_morphogen) < 0)
    fail_key(source, "preview_morphogen", "'" + spec.preview_morphogen + "' is no morphogen");
}

nlohmann::ordered_json reaction_diffusion_json(const ReactionDiffusionSpec& spec) {
  using oj = nlohmann::ordered_json;
  auto operand = [](const MapOperand& o) {
    return std::holds_alternative<double>(o) ? oj(std::get<double>(o)) : oj(std::get<std::string>(o));
  };
  auto values = [](const MorphogenValues& v) {
    oj j = oj::object();
    for (const auto& [name, value] : v) j[name] = value;
    return j;
  };
  oj j;
  j["model"] = spec.model;
  oj parameters = oj::object();
  for (const auto& [name, value] : spec.coefficients) parameters[name] = operand(value);
  j["parameters"] = parameters;
  oj noise = oj::object();
  for (const auto& [name, amplitude] : spec.parameter_noise) noise[name] = amplitude;
  j["parameter_noise"] = noise;
  oj morphogens = oj::object();
  for (size_t m = 0; m < spec.morphogens.size(); ++m) {
    const MorphogenSpec& g = spec.morphogens[m];
    oj entry;
    entry["diffusion"] = operand(g.diffusion);
    entry["initial"] = operand(g.initial);
    if (g.anisotropy) entry["anisotropy"] = {{"direction", g.anisotropy->direction}, {"ratio", operand(g.anisotropy->ratio)}};
    if (std::isfinite(g.minimum)) entry["minimum"] = g.minimum;
    entry["reaction"] = spec.reaction[m];
    morphogens[g.name] = entry;
  }
  j["morphogens"] = morphogens;
  oj initial;
  initial["noise"] = spec.initial.noise;
  if (spec.initial.seed_region)
    initial["seed_region"] = {{"map", spec.initial.seed_region->map}, {"values", values(spec.initial.seed_region->values)}};
  if (spec.initial.spots)
    initial["spots"] = {{"count", spec.initial.spots->count},
                        {"radius", spec.initial.spots->radius},
                        {"values", values(spec.initial.spots->values)}};
  j["initial"] = initial;
  if (spec.dirichlet) j["dirichlet"] = {{"map", spec.dirichlet->map}, {"values", values(spec.dirichlet->values)}};
  j["integrator"] = integrator_name(spec.integrator);
  j["preview_morphogen"] = spec.preview_morphogen;
  return j;
}

}  // namespace physarum
