#pragma once
// The pheromone's steady mean as the time-discrete model reaches it, against Eq. 5's U (the
// continuous model's). Both backends step the same discrete model, so the harness checks each arm
// against this value, not against U itself: with long steps the two differ by more than a margin.
//
// Decay (total mass M = sum_i m_i u_i; diffusion conserves it, a step deposits D in expectation):
//   forward Euler in s sub-steps of h = dt / s, deposits added after the transport:
//     M' = g M + D with g = (1 - k h)^s, fixed point D / (1 - g);
//   backward Euler, deposits added before the solve: (1 + k dt) M' = M + D, fixed point D / (k dt).
// U corresponds to D / (k dt), so the ratio is k dt / (1 - (1 - k dt / s)^s) for forward Euler:
// exactly 1 for one sub-step (the explicit decay and the lump deposit at the step's end cancel),
// about 1 + (k dt / 2)(1 - 1/s) for many (the field is sampled right after the step's deposit, at the
// top of a sawtooth whose mean over the sub-steps is U), and 1 for backward Euler.
//
// Activation (agents deposit once older than t_a; lifetimes are Exp(tau) rounded up to whole steps,
// so the per-step survival is q = exp(-dt / tau)): with t_a / dt = m + f (m whole, 0 <= f < 1), a
// newborn agent's first depositing step deposits the fraction 1 - f, so the depositing fraction is
// q^m (1 - f (1 - q)) instead of Eq. 5's exp(-t_a / tau). Equal when t_a / dt is whole or tau is
// infinite.
#include "common/model/diffusion_decay.hpp"

namespace physarum {

// k dt / (1 - (1 - k dt / s)^s) for forward Euler in `sub_steps` sub-steps; 1 for backward Euler.
double decay_discretisation_ratio(Integrator integrator, double decay_rate, double time_step, int sub_steps);

// q^m (1 - f (1 - q)) / exp(-t_a / tau) as above; 1 without turnover (tau infinite) or with t_a = 0.
double activation_discretisation_ratio(double time_step, double activation_time, double mean_lifetime);

}  // namespace physarum
