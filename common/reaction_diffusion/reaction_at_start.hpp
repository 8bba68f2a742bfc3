#pragma once
// The reaction terms at the initial state, checked before a run: a formula that is not finite there
// (u/0, log(-1), sqrt(-u) with u > 0) makes every free vertex it touches infinite or NaN after the
// first step, whichever integrator (forward Euler and IMEX both add R_m explicitly), and the run
// would be reported as diverged, which sends the user to the time step instead of the formula.
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"

#include <string>
#include <vector>

namespace physarum {

// Evaluates every R_m at every free vertex (not `fixed`: a held vertex never takes R) with the
// morphogens at `system.initial` and the coefficients at their values there. InputError at the first
// non-finite value, starting with where[m] (the formula's scene key) and naming the formula, the
// value, the intrinsic vertex and every variable's value there.
void check_reactions_finite_at_start(const ReactionDiffusionSystem& system, const std::vector<std::string>& where);

}  // namespace physarum
