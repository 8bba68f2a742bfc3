// The steady mean of the time-discrete model (common/model/discrete_steady_state.hpp): the factors
// against closed forms derived independently of the code. The reference simulation settling where
// the derivation says is tested in test_reference_simulation.cpp (DiscreteSteadyState*).
#include "common/model/discrete_steady_state.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace physarum {
namespace {

TEST(DiscreteSteadyState, DecayFactorMatchesClosedForms) {
  const double k_dt = 0.1;
  // One sub-step, and backward Euler: the fixed point is exactly D / (k dt).
  EXPECT_EQ(decay_discretisation_ratio(Integrator::Forward, 1.0, k_dt, 1), 1.0);
  EXPECT_EQ(decay_discretisation_ratio(Integrator::Backward, 1.0, k_dt, 40), 1.0);
  // Two sub-steps: g = (1 - k dt / 2)^2 = 1 - k dt + (k dt)^2 / 4, so the ratio is 1 / (1 - k dt / 4).
  EXPECT_NEAR(decay_discretisation_ratio(Integrator::Forward, 1.0, k_dt, 2), 1.0 / (1.0 - k_dt / 4.0), 1e-13);
  // Infinitely many: g -> exp(-k dt), the ratio k dt / (1 - exp(-k dt)).
  EXPECT_NEAR(decay_discretisation_ratio(Integrator::Forward, 1.0, k_dt, 1 << 20), k_dt / -std::expm1(-k_dt), 1e-7);
  // The rate and the step enter only through their product.
  EXPECT_DOUBLE_EQ(decay_discretisation_ratio(Integrator::Forward, 2.5, 0.04, 7),
                   decay_discretisation_ratio(Integrator::Forward, 1.0, 0.1, 7));
}

TEST(DiscreteSteadyState, ActivationFactorMatchesClosedForms) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(activation_discretisation_ratio(0.1, 0.2, inf), 1.0);
  EXPECT_EQ(activation_discretisation_ratio(0.1, 0.0, 1.0), 1.0);
  // A whole number of steps (0.2 / 0.1 in floating point is 2.0000000000000004): geometric
  // survival over 2 steps, exp(-0.1)^2 = exp(-0.2), the continuous factor itself: exactly 1, so that
  // the harness starts such scenes at U bit for bit as before.
  EXPECT_EQ(activation_discretisation_ratio(0.1, 0.2, 1.0), 1.0);
  EXPECT_EQ(activation_discretisation_ratio(0.04, 0.08, 0.2), 1.0);
  // t_a = 1.5 steps: survival q over the first step, then half of the second step deposits.
  const double q = std::exp(-0.1);
  EXPECT_NEAR(activation_discretisation_ratio(0.1, 0.15, 1.0), q * (1.0 - 0.5 * (1.0 - q)) / std::exp(-0.15), 1e-12);
}

}  // namespace
}  // namespace physarum
