// The two reaction-diffusion backends on one scene, built as `physarum run` builds them
// (api/backend_factory.hpp from the scene's system): the OpenCL backend follows the reference
// element by element within float rounding over many steps of a growing Gray-Scott pattern, in both
// integrators; each planted fault moves it far outside that; and a saved state restored into a fresh
// backend continues bit for bit (the checkpoint/resume contract of common/simulation/simulation_backend.hpp).
#include "common/simulation/simulation_state.hpp"
#include "reaction_diffusion_backend_pair.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;
using testing::largest_difference;
using testing::rd_backend;

// Gray-Scott spots on the sphere, from noise and a few seeded spots: the pattern grows (the state
// moves by O(1) in 200 steps), so the comparison is not of a state sitting still.
json gray_scott(const std::string& integrator) {
  return json::parse(R"({"mesh": "shape:sphere", "scale_to_area": 1.0, "model": "gray-scott",
    "parameters": {"F": 0.035, "k": 0.065},
    "morphogens": {"u": {"diffusion": 2e-5, "initial": 1.0}, "v": {"diffusion": 1e-5, "initial": 0.0}},
    "initial": {"noise": 0.01, "spots": {"count": 6, "radius": 0.08, "values": {"u": 0.5, "v": 0.25}}},
    "time_step": 1.0, "seed": 3, "integrator": ")" + integrator + R"("})");
}

TEST(ReactionDiffusionBackends, OpenCLFollowsTheReferenceAndFaultsDoNot) {
  for (const std::string integrator : {"forward", "imex"}) {
    const testing::LoadedReactionDiffusion rd = testing::load_rd_system(gray_scott(integrator));
    auto reference = rd_backend(rd, BackendChoice::Reference);
    auto device = rd_backend(rd, BackendChoice::OpenCL);
    auto swapped = rd_backend(rd, BackendChoice::OpenCL, "rd-swap-diffusion");
    auto no_feed = rd_backend(rd, BackendChoice::OpenCL, "rd-no-feed");
    const auto v0 = reference->field_values(1);
    for (auto* b : {reference.get(), device.get(), swapped.get(), no_feed.get()}) b->run(200);
    // How far the pattern itself moved: the scale the tolerance is set against.
    double moved = 0.0;
    const auto v = reference->field_values(1);
    for (size_t i = 0; i < v.size(); ++i) moved = std::max(moved, std::abs(v[i] - v0[i]));
    EXPECT_GT(moved, 0.05) << integrator;
    // float32 on the device: a few ulps (1e-7 of values of order 1) per step, which the stable
    // kinetics damp rather than amplify; 1e-4 is a thousand times the per-step rounding and a
    // five-hundredth of the motion.
    EXPECT_LT(largest_difference(*reference, *device), 1e-4) << integrator;
    EXPECT_GT(largest_difference(*reference, *swapped), 1e-2) << integrator;
    EXPECT_GT(largest_difference(*reference, *no_feed), 1e-2) << integrator;
  }
}

TEST(ReactionDiffusionBackends, ARestoredStateContinuesBitForBit) {
  for (const BackendChoice choice : {BackendChoice::Reference, BackendChoice::OpenCL}) {
    const testing::LoadedReactionDiffusion rd = testing::load_rd_system(gray_scott("forward"));
    auto whole = rd_backend(rd, choice);
    whole->run(30);
    auto first = rd_backend(rd, choice);
    first->run(12);
    const SimulationState saved = first->save_state();
    auto resumed = rd_backend(rd, choice);
    resumed->restore_state(saved);
    EXPECT_EQ(resumed->steps_taken(), 12);
    resumed->run(18);
    EXPECT_EQ(resumed->steps_taken(), whole->steps_taken());
    EXPECT_EQ(resumed->time(), whole->time());
    for (int m = 0; m < whole->dynamic_layer_count(); ++m)
      EXPECT_EQ(resumed->field_values(m), whole->field_values(m)) << to_string(choice) << " layer " << m;
    SimulationState wrong = saved;
    wrong.layers.pop_back();
    EXPECT_THROW(resumed->restore_state(wrong), InputError);
  }
}

}  // namespace
}  // namespace physarum
