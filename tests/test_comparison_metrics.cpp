// ComparisonMetrics shared between two arms (api/compare/comparison_arms.cpp shares one object when the
// arms run on one surface): each seed must still run its OWN scene's simulated time at its own
// time step and be measured against its own U. Measuring with the first arm's dt and U made
// `--arm time_step=X --arm time_step=X/2` run the second arm for half the simulated time, so its
// pattern looked about half as strong at every dt (a harness artefact, not a model one).
#include "common/setup/agent_inputs.hpp"
#include "common/harness/comparison_metrics.hpp"

#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"
#include "reference/agent_simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace physarum {
namespace {

Scene small_scene(double time_step, double deposit_rate) {
  const nlohmann::json overrides = {{"max_circumradius", 0.1},       {"agents", 300},
                                    {"time_step", time_step},        {"deposit_rate", deposit_rate},
                                    {"compare_burn_in", 0.1},        {"compare_duration", 0.1},
                                    {"compare_sample_interval", 0.05}, {"compare_eigenpairs", 8}};
  return load_scene(std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/resolved.json", overrides);
}

TEST(ComparisonMetrics, AMeasuredSeedRunsItsOwnScenesTimeStepAndU) {
  const Scene built_from = small_scene(0.01, 1.0);
  const Scene measured = small_scene(0.005, 2.0);  // half the step, twice the U of Eq. 5
  const PreparedSurface surface = prepare_scene_surface(built_from);
  const ComparisonMetrics metrics(surface, built_from);

  ReferenceAgentSimulation sim(surface.domain, constant_parameters(measured, surface.domain), simulation_settings(measured));
  const std::vector<double> m = metrics.measure_seed(sim, measured);
  // burn_in + duration = 0.2 s of the measured scene, in its 0.005 s steps (not 0.01 s ones).
  EXPECT_EQ(sim.steps_taken(), 40);
  EXPECT_NEAR(sim.time(), 0.2, 1e-12);
  // The field starts at, and stays near, the measured scene's U: mean / U is 1 (started from and
  // divided by the other scene's U, half of it, it drifts up towards 2: 1.09 over these 0.2 s).
  ASSERT_EQ(metrics.metrics().front().name, "mean_over_U");
  EXPECT_NEAR(m.front(), 1.0, 0.05);
}

}  // namespace
}  // namespace physarum
