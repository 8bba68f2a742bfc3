#include "common/reaction_diffusion/reaction_at_start.hpp"

#include "common/base/errors.hpp"
#include "common/base/value_range.hpp"
#include "common/reaction_diffusion/reaction_formula.hpp"

#include <cmath>
#include <stdexcept>

namespace physarum {
namespace {

std::string value_text(double x) {
  if (std::isnan(x)) return "NaN";
  if (std::isinf(x)) return x > 0 ? "+infinity" : "-infinity";
  return ValueRange::number(x);
}

}  // namespace

void check_reactions_finite_at_start(const ReactionDiffusionSystem& system, const std::vector<std::string>& where) {
  if (where.size() != system.reaction.size()) throw std::logic_error("check_reactions_finite_at_start: one place per formula");
  std::vector<std::string> names = system.morphogens;
  names.insert(names.end(), system.coefficient_names.begin(), system.coefficient_names.end());
  std::vector<double> values(names.size());
  std::vector<double*> addresses;
  for (double& v : values) addresses.push_back(&v);
  const size_t morphogens = system.morphogens.size(), vertices = system.mass.size();
  for (size_t m = 0; m < system.reaction.size(); ++m) {
    ReactionFormula formula(system.reaction[m], names, where[m]);
    formula.bind(addresses);
    for (size_t i = 0; i < vertices; ++i) {
      if (!system.fixed.empty() && system.fixed[i] != 0) continue;
      for (size_t k = 0; k < morphogens; ++k) values[k] = system.initial[k][i];
      for (size_t c = 0; c < system.coefficients.size(); ++c) values[morphogens + c] = system.coefficients[c][i];
      const double r = formula.evaluate_bound();
      if (std::isfinite(r)) continue;
      std::string at;
      for (size_t k = 0; k < names.size(); ++k) at.append(k ? ", " : "").append(names[k]).append(" = ").append(value_text(values[k]));
      throw InputError(where[m] + ": \"" + system.reaction[m] + "\" is " + value_text(r) +
                       " at the initial state (intrinsic vertex " + std::to_string(i) + ": " + at +
                       "), so the run could not take a single step; change the formula, or the initial values or "
                       "coefficients it is evaluated at");
    }
  }
}

}  // namespace physarum
