#pragma once
// The reaction–diffusion part of a scene (docs/reaction_diffusion.md): which model, its
// coefficients, its morphogens with their diffusion and initial state, the Dirichlet region and the
// morphogen the pictures show. Read from the scene's JSON object by read_reaction_diffusion (the keys
// "model", "parameters", "morphogens", "initial", "reaction", "dirichlet", "preview_morphogen");
// common/setup/reaction_diffusion_build.hpp turns it into a ReactionDiffusionSystem once the surface exists.
//
//   "model": "gray-scott" | "gierer-meinhardt" | "turing" | "activator-substrate" | "turing-spots" |
//            "meinhardt-spots" | "meinhardt-stripes" (common/reaction_diffusion/reaction_models.hpp),
//            or "custom" (implied by "reaction"); "physarum" (the default) is the agent model.
//   "parameters": {"F": 0.04, "k": "kmap"}        coefficients: numbers or scalar map names; a named
//                                                  model's defaults fill the rest
//   "parameter_noise": {"beta": 0.1}              a coefficient's value at each vertex + a uniform draw
//                                                  from [-a, a], fixed for the run (Turk's random factor
//                                                  beta); the 004 models have their beta noise by default
//   "reaction": {"u": "-u*v^2 + F*(1-u)", ...}    custom kinetics, 2..8 morphogens; the layer order is
//                                                  the ALPHABETICAL order of the names (a JSON object has
//                                                  no order of its own)
//   "morphogens": {"u": {"diffusion": 2e-5 | MAP, "initial": 1.0 | MAP,
//                        "anisotropy": {"direction": VECTOR_MAP, "ratio": r | MAP}, "minimum": 0 | null}}
//                  "diffusion" is the rate ALONG the direction, ratio x it the rate across (r > 0,
//                  a number or a scalar map; r = 1 is isotropic); "minimum" is a floor the value is raised to after every
//                  step (null: none; the turing model's v has 0 by default, as Turk's)
//   "initial": {"noise": a, "seed_region": {"map": MAP, "values": {"u": 0.5}},
//               "spots": {"count": n, "radius": r, "values": {"v": 0.25}}}
//   "dirichlet": {"map": MAP, "values": {"u": 0, "v": 30}}   vertices where MAP >= 0.5 are held fixed, at
//                                                            the values given, the others at their initial
//                                                            state (no noise: a held vertex is exactly it)
// A cascade (Turk 1992) is a morphogen's "initial" read from an earlier run ({"fields_full": ...} in
// common/maps/map_definition.hpp) with "dirichlet" over the earlier pattern's spots and no "values": the
// first layer stays frozen while the next grows between its spots.
//   "preview_morphogen": "v"                                   default: the second morphogen
#include "common/maps/map_definition.hpp"
#include "common/scene/model_tag.hpp"
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace physarum {

struct AnisotropySpec {
  std::string direction;  // a vector map
  MapOperand ratio = 1.0;  // rate across the direction / rate along it, > 0: a number or a scalar map
};

struct MorphogenSpec {
  std::string name;
  MapOperand diffusion = 0.0;  // m^2/s along the direction (isotropic: everywhere), number or scalar map
  MapOperand initial = 0.0;    // the starting value: a number, or a scalar map (an earlier run's field)
  std::optional<AnisotropySpec> anisotropy;
  double minimum = -std::numeric_limits<double>::infinity();  // the floor; -infinity: none
};

// Values per morphogen name (only the morphogens listed).
using MorphogenValues = std::vector<std::pair<std::string, double>>;

struct SeedRegionSpec {
  std::string map;  // a scalar map w, clamped to 0..1: value = (1 - w) initial + w values[m]
  MorphogenValues values;
};

struct SpotsSpec {
  int count = 0;        // spot centres, drawn by area from the scene's seed
  double radius = 0.0;  // m (after scale_to_area), straight-line distance from the centre
  MorphogenValues values;
};

struct ReactionInitialSpec {
  double noise = 0.0;  // every free vertex and morphogen gets + noise x uniform(-1, 1)
  std::optional<SeedRegionSpec> seed_region;
  std::optional<SpotsSpec> spots;
};

struct DirichletSpec {
  std::string map;         // scalar map: fixed where >= 0.5
  MorphogenValues values;  // the held value per morphogen (those not listed keep their initial state)
};

struct ReactionDiffusionSpec {
  std::string model;  // a named model or "custom"
  std::vector<MorphogenSpec> morphogens;  // layer order
  std::vector<std::string> reaction;      // R_m per morphogen, muparser syntax
  std::vector<std::pair<std::string, MapOperand>> coefficients;  // every coefficient name, in order
  // Coefficients with per-vertex noise: name, amplitude a >= 0 (uniform in [-a, a], fixed for the run).
  std::vector<std::pair<std::string, double>> parameter_noise;
  ReactionInitialSpec initial;
  std::optional<DirichletSpec> dirichlet;
  Integrator integrator = Integrator::Forward;
  std::string preview_morphogen;  // a morphogen name

  int morphogen_index(const std::string& name) const;  // -1 when none
};

// The scene keys this file reads (besides "integrator", shared with the agent model).
const std::vector<std::string>& reaction_diffusion_keys();

// nullopt for the agent model ("model" absent or "physarum", and no "reaction"); InputError naming
// the key for anything wrong: an unknown model or field, 1 or more than 8 morphogens, a formula with
// an unknown name (and its position), negative diffusion, ratio <= 0, a value for a morphogen the
// model does not have, an RD key in a physarum scene. Map names are checked by
// validate_reaction_diffusion (the maps are read separately).
std::optional<ReactionDiffusionSpec> read_reaction_diffusion(const nlohmann::json& scene, const std::string& source);

// Every map the spec names exists in `maps` and is of the needed kind; the numbers are in range;
// the formulas parse. InputError naming the key.
void validate_reaction_diffusion(const ReactionDiffusionSpec& spec, const MapSet& maps, const std::string& source);

// The spec as run.json shows it.
nlohmann::ordered_json reaction_diffusion_json(const ReactionDiffusionSpec& spec);

// The scene layer's names for the above (common/scene/scene_models.hpp).
struct Scene;
inline std::optional<ReactionDiffusionSpec> read_model(ModelTag<ReactionDiffusionSpec>, const nlohmann::json& scene,
                                                       const std::string& source) {
  return read_reaction_diffusion(scene, source);
}
inline std::string model_key(const ReactionDiffusionSpec& spec) { return spec.model; }
// A reaction's time scale is its own: the harness averages over the second half of its run.
inline bool compares_over_its_run_length(const ReactionDiffusionSpec&) { return true; }
inline void validate_model(const ReactionDiffusionSpec& spec, const MapSet& maps, const std::string& source) {
  validate_reaction_diffusion(spec, maps, source);
}
inline nlohmann::ordered_json model_json(const ReactionDiffusionSpec& spec, const Scene&) {
  return reaction_diffusion_json(spec);
}

}  // namespace physarum
