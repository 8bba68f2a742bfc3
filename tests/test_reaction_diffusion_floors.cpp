// Floors (ReactionDiffusionSystem::minimum): Turk's Turing model grown from noise keeps v >= 0 and
// stays finite long after the same run without the floor has run away (the reason the turing model
// has v's floor at 0 by default, as Turk's own implementation clamps it), and the OpenCL backend
// applies the floor where the reference does: it follows the reference through a run in which the
// floor holds many vertices, in both integrators.
#include "common/simulation/simulation_state.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "reaction_diffusion_scene.hpp"
#include "api/backend_factory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;

// The rdcompare Turing scene (tools/scenes/compare/turing_sphere.json) on a coarser sphere: Turk's
// alpha = 16, beta = 12 at rho = 1 from 0.1 % noise about the uniform state (4, 4), D_u / D_v = 8,
// above the critical ratio, so the pattern grows and its troughs reach v = 0 within ~10 s.
json turing(const json& v_minimum, const std::string& integrator) {
  json j = json::parse(R"({"mesh": "shape:sphere", "scale_to_area": 1.0, "max_circumradius": 0.03, "model": "turing",
    "parameters": {"rho": 1.0, "alpha": 16.0, "beta": 12.0},
    "morphogens": {"u": {"diffusion": 1.6e-3, "initial": 4.0}, "v": {"diffusion": 2e-4, "initial": 4.0}},
    "initial": {"noise": 0.001}, "time_step": 0.1, "seed": 1})");
  j["integrator"] = integrator;
  if (!v_minimum.is_discarded()) j["morphogens"]["v"]["minimum"] = v_minimum;
  return j;
}

std::unique_ptr<SimulationBackend> backend(const testing::LoadedReactionDiffusion& rd, BackendChoice choice) {
  static const opencl::ComputeContext compute = opencl::make_compute_context("");
  return make_reaction_diffusion_backend(choice, choice == BackendChoice::OpenCL ? &compute : nullptr, rd.surface.domain,
                                         rd.system, opencl::OpenCLBackendOptions{});
}

bool finite_and_bounded(const IntrinsicVertexData<double>& values, double bound) {
  return std::all_of(values.begin(), values.end(), [&](double x) { return std::isfinite(x) && std::abs(x) < bound; });
}

TEST(ReactionDiffusionFloors, TuringKeepsVNonNegativeAndFiniteWhereTheUnflooredRunRunsAway) {
  const testing::LoadedReactionDiffusion floored = testing::load_rd_system(turing(json::value_t::discarded, "forward"));
  ASSERT_EQ(floored.system.minimum.size(), 2u);
  EXPECT_EQ(floored.system.minimum[1], 0.0);  // the turing model's default, as Turk's
  EXPECT_EQ(floored.system.minimum[0], -std::numeric_limits<double>::infinity());
  const testing::LoadedReactionDiffusion free = testing::load_rd_system(turing(nullptr, "forward"));
  EXPECT_EQ(free.system.minimum[1], -std::numeric_limits<double>::infinity());

  auto with_floor = backend(floored, BackendChoice::Reference);
  auto without = backend(free, BackendChoice::Reference);
  with_floor->run(600);  // 60 s
  without->run(600);
  const IntrinsicVertexData<double> v = with_floor->field_values(1), u = with_floor->field_values(0);
  EXPECT_TRUE(finite_and_bounded(u, 1e3));
  EXPECT_TRUE(finite_and_bounded(v, 1e3));
  EXPECT_GE(*std::min_element(v.begin(), v.end()), 0.0);
  // The floor is what holds it: many vertices sit exactly on it.
  const auto on_floor = std::count(v.begin(), v.end(), 0.0);
  EXPECT_GT(on_floor, static_cast<long>(v.size() / 20)) << "vertices at v = 0: " << on_floor;
  // Without it the same run leaves every bound (or stops being a number).
  EXPECT_FALSE(finite_and_bounded(without->field_values(1), 1e3) && finite_and_bounded(without->field_values(0), 1e3));
}

// From one grown state (the reference's after 15 s, many vertices on the floor), both backends take
// 10 more steps. Not from the noise: the pattern grows from it at ~0.8 / s, so float and double runs
// drift apart by amplified rounding long before a floor matters. Within 10 steps the rounding stays
// small, while a device without the floor would put v below zero by about rho * beta * dt = 1.2 in a
// single step.
TEST(ReactionDiffusionFloors, OpenCLAppliesTheFloorWhereTheReferenceDoes) {
  for (const std::string integrator : {"forward", "imex"}) {
    const testing::LoadedReactionDiffusion rd = testing::load_rd_system(turing(json::value_t::discarded, integrator));
    auto grown = backend(rd, BackendChoice::Reference);
    grown->run(150);
    const SimulationState state = grown->save_state();
    auto reference = backend(rd, BackendChoice::Reference);
    auto device = backend(rd, BackendChoice::OpenCL);
    reference->restore_state(state);
    device->restore_state(state);
    reference->run(10);
    device->run(10);
    const IntrinsicVertexData<double> a = reference->field_values(1), b = device->field_values(1);
    ASSERT_GT(std::count(a.begin(), a.end(), 0.0), static_cast<long>(a.size() / 20))
        << integrator << ": few vertices on the floor; the check would be empty";
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    EXPECT_GE(*std::min_element(b.begin(), b.end()), 0.0) << integrator;
    EXPECT_LT(worst, 1e-3) << integrator;
  }
}

}  // namespace
}  // namespace physarum
