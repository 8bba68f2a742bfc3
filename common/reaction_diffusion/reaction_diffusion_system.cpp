#include "common/reaction_diffusion/reaction_diffusion_system.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <set>

namespace physarum {
namespace {

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

}  // namespace

void check_reaction_diffusion_system(const ReactionDiffusionSystem& s, int n, const std::string& who) {
  const size_t un = static_cast<size_t>(n);
  const size_t count = s.morphogens.size();
  if (count < 2 || count > kMaxMorphogens)
    throw InputError(who + ": " + std::to_string(count) + " morphogens (2 to " + std::to_string(kMaxMorphogens) +
                     " are supported)");
  if (s.reaction.size() != count)
    throw InputError(who + ": " + std::to_string(s.reaction.size()) + " reaction formulas for " +
                     std::to_string(count) + " morphogens");
  if (s.coefficients.size() != s.coefficient_names.size())
    throw InputError(who + ": " + std::to_string(s.coefficients.size()) + " coefficient arrays for " +
                     std::to_string(s.coefficient_names.size()) + " coefficient names");
  std::set<std::string> names;
  for (const auto* list : {&s.morphogens, &s.coefficient_names})
    for (const std::string& name : *list) {
      if (!is_identifier(name))
        throw InputError(who + ": '" + name + "' is not a usable name (letters, digits, '_', not starting with a digit)");
      if (!names.insert(name).second) throw InputError(who + ": the name '" + name + "' is given twice");
    }
  if (s.stiffness.size() != count || s.initial.size() != count)
    throw InputError(who + ": " + std::to_string(s.stiffness.size()) + " stiffness matrices and " +
                     std::to_string(s.initial.size()) + " initial states for " + std::to_string(count) + " morphogens");
  if (s.mass.size() != un)
    throw InputError(who + ": " + std::to_string(s.mass.size()) + " masses for " + std::to_string(n) + " vertices");
  for (int i = 0; i < n; ++i)
    if (!(s.mass[i] > 0.0) || !std::isfinite(s.mass[i]))
      throw InputError(who + ": vertex " + std::to_string(i) + " has lumped mass " + std::to_string(s.mass[i]) +
                       " (must be > 0)");
  for (size_t c = 0; c < s.coefficients.size(); ++c) {
    if (s.coefficients[c].size() != un)
      throw InputError(who + ": coefficient '" + s.coefficient_names[c] + "' has " +
                       std::to_string(s.coefficients[c].size()) + " values for " + std::to_string(n) + " vertices");
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(s.coefficients[c][i]))
        throw InputError(who + ": coefficient '" + s.coefficient_names[c] + "' is not finite at vertex " + std::to_string(i));
  }
  for (size_t m = 0; m < count; ++m) {
    const CsrMatrix& K = s.stiffness[m];
    if (K.rows != n || K.cols != n || K.row_start.size() != un + 1)
      throw InputError(who + ": the stiffness of '" + s.morphogens[m] + "' is " + std::to_string(K.rows) + " x " +
                       std::to_string(K.cols) + " for " + std::to_string(n) + " vertices");
    if (K.row_start != s.stiffness[0].row_start || K.column != s.stiffness[0].column)
      throw InputError(who + ": the stiffness of '" + s.morphogens[m] + "' has another sparsity pattern than that of '" +
                       s.morphogens[0] + "' (all share the Laplacian's)");
    for (double v : K.value)
      if (!std::isfinite(v)) throw InputError(who + ": the stiffness of '" + s.morphogens[m] + "' has a non-finite entry");
    if (s.initial[m].size() != un)
      throw InputError(who + ": the initial state of '" + s.morphogens[m] + "' has " +
                       std::to_string(s.initial[m].size()) + " values for " + std::to_string(n) + " vertices");
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(s.initial[m][i]))
        throw InputError(who + ": the initial state of '" + s.morphogens[m] + "' is not finite at vertex " +
                         std::to_string(i));
  }
  if (!s.fixed.empty() && s.fixed.size() != un)
    throw InputError(who + ": " + std::to_string(s.fixed.size()) + " held-vertex flags for " + std::to_string(n) +
                     " vertices");
  if (!(s.time_step > 0.0) || !std::isfinite(s.time_step))
    throw InputError(who + ": time step " + std::to_string(s.time_step) + " must be > 0");
  if (s.substeps < 1) throw InputError(who + ": substeps " + std::to_string(s.substeps) + " must be >= 1");
  if (s.integrator == Integrator::Backward)
    throw InputError(who + ": integrator 'backward' is the agent model's; a reaction-diffusion system is forward or imex");
  if (!s.minimum.empty() && s.minimum.size() != count)
    throw InputError(who + ": " + std::to_string(s.minimum.size()) + " floors for " + std::to_string(count) +
                     " morphogens (one per morphogen, or none)");
  for (const double floor : s.minimum)
    if (std::isnan(floor) || floor == std::numeric_limits<double>::infinity())
      throw InputError(who + ": every floor must be finite or -infinity");
}

}  // namespace physarum
