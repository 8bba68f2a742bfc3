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
  // A whole number of steps (0.2 / 0.1 is 2.0000000000000004: within rounding counts): geometric
  // survival over them is exactly exp(-t_a / tau), so the factor is 1 (returned as such, not as the
  // ratio of two roundings of it).
  if (std::abs(steps - std::round(steps)) < 1e-9 * std::max(1.0, steps)) return 1.0;
  const double whole = std::floor(steps);
  const double f = steps - whole;
  const double q = std::exp(-time_step / mean_lifetime);
  return std::pow(q, whole) * (1.0 - f * (1.0 - q)) / std::exp(-activation_time / mean_lifetime);
}

}  // namespace physarum
