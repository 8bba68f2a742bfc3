#include "common/model/discrete_steady_state.hpp"

#include <cmath>

namespace physarum {

double decay_discretisation_ratio(Integrator integrator, double decay_rate, double time_step, int sub_steps) {
  const double k_dt = decay_rate * time_step;
  if (integrator == Integrator::Backward || sub_steps <= 1 || !(k_dt > 0.0)) return 1.0;
  const double g = std::pow(1.0 - k_dt / sub_steps, sub_steps);
  return k_dt / (1.0 - g);
}

double activation_discretisation_ratio(double time_step, double activation_time, double mean_lifetime) {
  if (std::isinf(mean_lifetime) || !(activation_time > 0.0)) return 1.0;
  const double steps = activation_time / time_step;
  // A ratio within rounding of a whole number is that number (0.2 / 0.1 is 2.0000000000000004).
  const double whole = std::abs(steps - std::round(steps)) < 1e-9 * std::max(1.0, steps) ? std::round(steps)
                                                                                           : std::floor(steps);
  const double f = std::max(0.0, steps - whole);
  const double q = std::exp(-time_step / mean_lifetime);
  return std::pow(q, whole) * (1.0 - f * (1.0 - q)) / std::exp(-activation_time / mean_lifetime);
}

}  // namespace physarum
