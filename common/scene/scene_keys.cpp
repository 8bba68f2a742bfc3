#include "common/scene/scene_keys.hpp"

#include "common/scene/scene.hpp"

#include <algorithm>
#include <limits>

namespace physarum {
namespace {

SceneKey setting(std::string_view name, KeyKind kind, bool required, ValueRange range, std::string_view unit,
                 std::string default_text, std::string_view doc, std::string_view allowed_text = {}) {
  return SceneKey{name, kind, required, range, unit, allowed_text, std::move(default_text), doc, std::nullopt, false};
}

SceneKey parameter_key(const ParameterSpec& p) {
  return SceneKey{p.key,
                  p.null_means_infinite ? KeyKind::NumberOrNull : KeyKind::Number,
                  !p.default_value.has_value(),
                  p.range,
                  p.unit,
                  {},
                  p.default_value ? ValueRange::number(*p.default_value) : std::string(),
                  p.doc,
                  p.id,
                  true};
}

std::vector<SceneKey> build_keys() {
  using K = KeyKind;
  std::vector<SceneKey> keys = {
      setting("mesh", K::String, true, {}, "", "",
              "a mesh file (OBJ, OFF, PLY, STL), relative to the scene file's folder or absolute, or shape:NAME"),
      setting("scale_to_area", K::Number, false, kPositive, "m^2", "",
              "rescale the input about the origin to this area"),
      setting("max_circumradius", K::Number, false, kPositive, "m", "",
              "refine until every intrinsic face's circumradius is at most this (after scaling)"),
      // Refinement by circumcenter insertion terminates for angle bounds up to about 30 degrees.
      setting("min_angle", K::Number, false, ValueRange{0.0, false, 30.0, false}, "deg", "0 (off)",
              "refine faces with a smaller angle"),
      setting("agents", K::Integer, false, ValueRange{1.0, false, 2147483647.0, false}, "", "required (physarum)",
              "number of agents N"),
      setting("time_step", K::Number, true, kPositive, "s", "", "time step dt"),
      // ---- the field model (common/scene/scene_reaction_diffusion.hpp) ----
      setting("model", K::String, false, {}, "", "\"physarum\"",
              "the field model: the agent model, a named reaction-diffusion model (common/reaction_diffusion/reaction_models.cpp) "
              "or custom kinetics (\"reaction\"); a reaction-diffusion scene takes none of the agent keys",
              "\"physarum\", \"gray-scott\", \"gierer-meinhardt\", \"turing\", \"activator-substrate\", \"turing-spots\", "
              "\"meinhardt-spots\", \"meinhardt-stripes\", \"custom\", \"growth\" (a reaction-diffusion system on a growing "
              "thin shell, paper 003: the keys below down to \"dilute\")"),
      // ---- the growth model (common/scene/scene_growth.hpp, docs/growth.md) ----
      setting("reaction_diffusion", K::Object, false, {}, "", "gray-scott, u = 1, v = 0 but v = 1, u = 0 near the sheet's centre",
              "growth: the reaction-diffusion system on the sheet, with the keys of a reaction-diffusion scene (model, "
              "parameters, morphogens, initial, dirichlet, preview_morphogen, integrator; time_step here or at the top)",
              "{\"model\": ..., \"parameters\": {..}, \"morphogens\": {..}, \"initial\": {..}, ...}"),
      setting("shell", K::Object, false, {}, "m, Pa", "aluminium: 0.002 m, 7e10 Pa, 0.33; perturbation 1e-3, tolerance 1e-8, "
              "100 iterations (then the step in 2, 4, 8 sub-steps)",
              "growth: the thin elastic sheet (St. Venant-Kirchhoff membrane, discrete-hinge bending), the out-of-plane "
              "nudge before each growth step (a fraction of the mean rest edge length) and Newton's stopping rule (a "
              "residual strain: largest free force / (Y h mean edge))",
              "{\"thickness\": h > 0, \"young_modulus\": Y > 0, \"poisson_ratio\": -1 < nu < 0.5, \"perturbation\": 0..0.5, "
              "\"tolerance\": > 0, \"max_iterations\": n}"),
      setting("growth", K::Object, false, {}, "", "polynomial, m = 0, n = 1, gamma = 0.05, rate = 0.01",
              "growth: each face's rest lengths grow by 1 + rate g(a, b) per growth step, g = a^m b^n / gamma (Eq. 7) or "
              "lambda exp(a^m b^n / gamma - 1) (Eq. 6) of the face's mean morphogens a, b (default the first two); or a "
              "prescribed target stretch of rest lengths (a scalar map or a number; 1 = none) reached in equal factors, a "
              "map growing each rest edge by the mean of its ends' values; "
              "either anisotropic along a vector map, growing `across` times as much across it",
              "{\"function\": \"polynomial\" or \"exponential\", \"m\", \"n\", \"gamma\", \"lambda\", \"rate\", \"a\": MORPHOGEN, "
              "\"b\": MORPHOGEN} or {\"stretch\": SCALAR_MAP or s > 0}, + \"anisotropy\": {\"direction\": VECTOR_MAP, "
              "\"across\": 0..10}"),
      setting("schedule", K::Object, false, {}, "steps", "0 reaction steps, 1 growth step, not interleaved",
              "growth: reaction_steps RD steps then growth_steps growth steps, or (interleaved) reaction_steps RD steps "
              "before each growth step; the run's length (each RD or growth step is one step of physarum run)",
              "{\"reaction_steps\": N >= 0, \"growth_steps\": G >= 1, \"interleaved\": true or false}"),
      setting("refine", K::Object, false, {}, "m", "none",
              "growth: after each growth step, rest edges longer than max_edge are split at their midpoints "
              "(longest first; the children tile their parent's rest shape; concentrations averaged)",
              "{\"max_edge\": L > 0}"),
      setting("dilute", K::Boolean, false, {}, "", "false",
              "growth: scale every concentration by old / new rest mass after each growth step, so each morphogen's "
              "amount is conserved as the tissue grows"),
      setting("parameters", K::Object, false, {}, "", "the model's",
              "reaction-diffusion coefficients (F, k, rho, ...): numbers or scalar map names",
              "{\"NAME\": number or SCALAR_MAP, ...}"),
      setting("parameter_noise", K::Object, false, {}, "", "the model's (beta: 0.1 for turing-spots, meinhardt-spots, "
              "meinhardt-stripes; none for the others)",
              "reaction-diffusion: per-vertex noise of a coefficient, fixed for the run: its value + a uniform draw from "
              "[-a, a] (the random factor beta of Turk's and Meinhardt's systems, `004_…`)",
              "{\"NAME\": a >= 0, ...}"),
      setting("morphogens", K::Object, false, {}, "m^2/s", "the model's",
              "per morphogen: diffusion rate (along the anisotropy direction; across = ratio x it), initial value "
              "(a number, or a scalar map such as an earlier run's field: a cascade), floor the value is raised to after "
              "every step (turing's v: 0, as Turk's; null: none)",
              "{\"u\": {\"diffusion\": D >= 0 or SCALAR_MAP, \"initial\": x or SCALAR_MAP, \"anisotropy\": {\"direction\": VECTOR_MAP, "
              "\"ratio\": r > 0 or SCALAR_MAP}, \"minimum\": x or null}, ...}"),
      setting("reaction", K::Object, false, {}, "", "the model's",
              "custom kinetics: one formula per morphogen (2 to 8; layer order = alphabetical), over the "
              "morphogens and parameters; + - * / ^, exp log sqrt abs min max sin cos tanh",
              "{\"u\": \"-u*v^2 + F*(1-u)\", \"v\": \"u*v^2 - (F+k)*v\"}"),
      setting("initial", K::Object, false, {}, "", "uniform",
              "reaction-diffusion initial state beyond the uniform one: noise, a seed region, random spots",
              "{\"noise\": a >= 0, \"seed_region\": {\"map\": SCALAR_MAP, \"values\": {..}}, \"spots\": {\"count\": n, "
              "\"radius\": m, \"values\": {..}}}"),
      setting("dirichlet", K::Object, false, {}, "", "none (no-flux)",
              "reaction-diffusion: every morphogen held fixed where the map is >= 0.5, at the given values or else at "
              "its initial state (no noise there): with an earlier run's field as \"initial\", a frozen first "
              "layer that the next pattern grows around (Turk's cascade)",
              "{\"map\": SCALAR_MAP, \"values\": {\"u\": x, ...}}"),
      setting("preview_morphogen", K::String, false, {}, "", "the second morphogen",
              "reaction-diffusion: the morphogen preview.png, texture.png and result.glb show", "a morphogen name"),
      setting("maps", K::Object, false, {}, "", "",
              "named surface maps the parameters and controls below refer to (README \"Surface maps\"; "
              "common/maps/map_definition.hpp); coordinates are the input mesh's, before scale_to_area",
              "{\"NAME\": SOURCE, ...}: a number, ply, fields_full (an earlier run's fields_full.ply on the same "
              "surface, exact), texture, sphere, box, half_space, segments, axis, map+range, invert, "
              "threshold, clamp, sum, product, min, max (scalar); direction, toward, away_from, ply face_property (vector)"),
  };
  for (const ParameterSpec& p : kParameterTable) keys.push_back(parameter_key(p));
  const std::vector<SceneKey> controls = {
      setting("read_stimuli", K::List, false, {}, "concentration", "none",
              "static layers added to what the sensors read: sum of weight x map (weight < 0 repels)",
              "[{\"map\": SCALAR_MAP, \"weight\": w}, ...]"),
      setting("write_stimuli", K::List, false, {}, "amount/s", "none",
              "pheromone added at rate x map per second, independent of the agents (rate < 0 removes; never below 0)",
              "[{\"map\": SCALAR_MAP, \"rate\": r}, ...]"),
      setting("spawn_weight", K::NumberOrString, false, kNonNegative, "", "uniform",
              "multiplies face area in the (re)spawn distribution; zero-weight regions get no agents; not all zero",
              "a scalar map name (values >= 0) or a number > 0"),
      setting("bias", K::Object, false, {}, "deg/s", "none",
              "directional bias (Fig. 6): agents turn toward the closest of the n-fold copies of the direction",
              "{\"direction\": VECTOR_MAP, \"strength\": deg/s >= 0 or SCALAR_MAP, \"symmetry\": 1..8 (default 1)}"),
      setting("spawn_heading", K::String, false, {}, "", "\"random\"",
              "heading of (re)spawned agents: uniform, or along the bias direction (Fig. 8; needs bias)",
              "\"random\" or \"bias\""),
      setting("boundary", K::String, false, {}, "", "\"reflect\"",
              "agents reaching a boundary edge are mirrored, or removed and respawned (Fig. 18's margin)",
              "\"reflect\" or \"terminate\""),
      setting("species", K::List, false, {}, "", "one species",
              "competing species (MoMaS): one pheromone layer each, deposited by that species only; each entry "
              "overrides parameters above (numbers or maps); the top-level agents, if given, must be their sum",
              "[{\"agents\": N, PARAMETER: value or map, ...}, ...]"),
      setting("sensing", K::List, false, {}, "", "identity",
              "what species i's sensors read: sum over j of m_ij x layer_j (row i = species i; needs species)",
              "K x K finite numbers, e.g. [[1, -0.5], [-0.5, 1]]"),
  };
  keys.insert(keys.end(), controls.begin(), controls.end());
  const ComparisonSettings c;  // the harness's documented defaults, shown as they are in code
  const auto shown = [](double v) { return ValueRange::number(v); };
  const std::vector<SceneKey> rest = {
      setting("integrator", K::String, false, {}, "", "\"forward\"",
              "time integration of the pheromone PDE; of a reaction-diffusion system: explicit with automatic "
              "sub-steps, or implicit diffusion with explicit reaction",
              "\"forward\" or \"backward\" (Euler); reaction-diffusion: \"forward\" or \"imex\""),
      setting("seed", K::Integer, false, ValueRange{0.0, false, 4294967295.0, false}, "", "1", "random seed"),
      setting("steps", K::Integer, false, ValueRange{1.0, false, 1.0e15, false}, "", "",
              "run length in steps (at most one of steps, sim_time)"),
      setting("sim_time", K::Number, false, kPositive, "s", "", "run length in simulated seconds"),
      setting("colormap", K::StringOrObject, false, {}, "", "\"viridis\"",
              "colours of pheromone.ply and preview.png: levels (in multiples of U), gamma, remap curve, map "
              "(common/color/color_map_json.hpp; `physarum colormap IMAGE` extracts one from a picture)",
              "a built-in name (viridis, magma, inferno, grey, physarum, moss, ocean, ember, lichen), a path to a "
              "MAP.json, a list of colours `\"#rrggbb,#rrggbb,...\"` (equally spaced, first to last), or an inline "
              "{\"stops\", \"gamma\", \"remap\", \"levels\"} object"),
      // ---- the differential harness (ComparisonSettings, tools/scenes/compare/README.md) ----
      setting("compare_burn_in", K::Number, false, kNonNegative, "s", shown(c.burn_in), "compare: simulated and discarded per seed (reaction-diffusion: half the run unless given)"),
      setting("compare_duration", K::Number, false, kPositive, "s", shown(c.duration), "compare: simulated and averaged per seed (reaction-diffusion: the other half unless given)"),
      setting("compare_sample_interval", K::Number, false, kPositive, "s", shown(c.sample_interval), "compare: between two samples"),
      setting("compare_seeds", K::Integer, false, ValueRange{2.0, false, 10000.0, false}, "",
              std::to_string(c.max_seeds), "compare: most seeds per arm (the sequential test stops when it can)"),
      setting("compare_margin_mean", K::Number, false, kPositive, "", shown(c.margin_mean), "compare: margin on mean / U (reaction-diffusion: relative, on each morphogen's mean)"),
      setting("compare_margin_coverage", K::Number, false, kPositive, "", shown(c.margin_coverage),
              "compare: margin on each coverage fraction"),
      setting("compare_margin_spectrum", K::Number, false, kPositive, "", shown(c.margin_spectrum),
              "compare: relative margin on each spectral band power"),
      setting("compare_margin_density", K::Number, false, kPositive, "", shown(c.margin_density),
              "compare: relative margin on the agent-density dispersion"),
      setting("compare_margin_detail", K::Number, false, kPositive, "", shown(c.margin_detail),
              "compare: relative margin on each detail energy (reaction-diffusion: on each morphogen's variance / mean^2)"),
      setting("compare_bands", K::Integer, false, ValueRange{1.0, false, 64.0, false}, "", shown(c.spectrum_bands),
              "compare: manifold-harmonic (and radial) bands"),
      setting("compare_eigenpairs", K::Integer, false, ValueRange{4.0, false, 2000.0, false}, "", shown(c.eigenpairs),
              "compare: manifold harmonics computed for the bands"),
  };
  keys.insert(keys.end(), rest.begin(), rest.end());
  return keys;
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

std::string map_alternative(const SceneKey& k) {
  if (!k.accepts_map) return "";
  std::string text = "; or a scalar map: NAME or {\"map\": NAME, \"range\": [lo, hi]}";
  if (k.parameter && map_value_range(parameter_spec(*k.parameter)) != k.range)
    text += " whose values " + map_value_range(parameter_spec(*k.parameter)).describe().substr(std::string("must be ").size()) +
            " (0 = a sink)";
  return text;
}

std::string allowed_column(const SceneKey& k) {
  switch (k.kind) {
    case KeyKind::String:
      return std::string(k.allowed_text.empty() ? "text" : k.allowed_text);
    case KeyKind::Integer:
      return "integer, " + k.range.describe().substr(std::string("must be ").size());
    case KeyKind::Number:
      return k.range.describe().substr(std::string("must be ").size()) + map_alternative(k);
    case KeyKind::NumberOrNull:
      return k.range.describe().substr(std::string("must be ").size()) + ", or null" + map_alternative(k);
    case KeyKind::StringOrObject:
    case KeyKind::Object:
    case KeyKind::List:
    case KeyKind::NumberOrString:
      return std::string(k.allowed_text);
    case KeyKind::Boolean:
      return "true or false";
  }
  return {};
}

}  // namespace

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> keys = build_keys();
  return keys;
}

const SceneKey* find_scene_key(std::string_view name) {
  for (const SceneKey& k : scene_keys())
    if (k.name == name) return &k;
  return nullptr;
}

// One that contains the name (or is contained in it, as "decay" in "decay_rate"), otherwise the one
// at the smallest edit distance.
std::string closest_scene_key(std::string_view name) {
  for (const SceneKey& k : scene_keys())
    if (name.size() >= 3 && (k.name.find(name) != std::string_view::npos || name.find(k.name) != std::string_view::npos))
      return std::string(k.name);
  std::string best;
  size_t best_distance = std::numeric_limits<size_t>::max();
  for (const SceneKey& k : scene_keys()) {
    const size_t d = edit_distance(name, k.name);
    if (d < best_distance) best_distance = d, best = std::string(k.name);
  }
  return best;
}

std::string scene_keys_markdown() {
  std::string out = "| key | unit | allowed | default | meaning |\n|---|---|---|---|---|\n";
  for (const SceneKey& k : scene_keys()) {
    const std::string fallback = k.required ? "required" : (k.default_text.empty() ? "optional" : k.default_text);
    out += "| `" + std::string(k.name) + "` | " + std::string(k.unit) + " | " + allowed_column(k) + " | " + fallback +
           " | " + std::string(k.doc) + " |\n";
  }
  return out;
}

}  // namespace physarum
