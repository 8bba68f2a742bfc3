#pragma once
// The named reaction–diffusion models a scene selects with "model": each is defined ONCE here, by its
// reaction formulas (muparser syntax, common/reaction_diffusion/reaction_formula.hpp) over its morphogens and
// coefficients, with the default coefficients, diffusion rates and initial values of the paper the
// model comes from. Both backends evaluate these formulas, so a named model and the same formulas
// given as a custom "reaction" are one and the same system.
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace physarum {

struct ReactionModel {
  std::string name;                     // the scene's "model" value
  std::vector<std::string> morphogens;  // in layer order
  std::vector<std::string> reaction;    // R_m, one per morphogen
  std::vector<std::pair<std::string, double>> coefficients;  // name, default value
  std::vector<double> diffusion;        // default rate per morphogen (m^2/s)
  std::vector<double> initial;          // default uniform initial value per morphogen
  std::vector<double> minimum;          // default floor per morphogen (-infinity: none)
  std::string source;                   // where the equations and defaults come from
  // Default per-vertex noise of coefficients (name, amplitude a: each vertex's value gets a uniform
  // draw from [-a, a], fixed for the run): Turk's and Meinhardt's random factor beta, which the
  // patterns of `004_…` grow from. Empty for the models that start from noisy initial values instead.
  std::vector<std::pair<std::string, double>> parameter_noise;
};

// gray-scott, gierer-meinhardt, turing, activator-substrate, and the three systems of the appendix of
// `004_…`: turing-spots, meinhardt-spots, meinhardt-stripes.
const std::vector<ReactionModel>& reaction_models();
// nullptr when `name` is no named model.
const ReactionModel* find_reaction_model(std::string_view name);
// "gray-scott, gierer-meinhardt, ..." (for messages).
std::string reaction_model_names();

}  // namespace physarum
