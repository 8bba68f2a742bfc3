// The three systems of the appendix of `004_…` (Phan & Grimm; common/reaction_diffusion/reaction_models.cpp):
// their per-vertex beta noise ("parameter_noise") against its stated distribution, the uniform
// steady state of Meinhardt's five-morphogen stripe system on both backends, and the OpenCL step of
// five morphogens (the wide-vector path) following the reference while its planted fault does not.
#include "reaction_diffusion_backend_pair.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;
using testing::largest_difference;
using testing::rd_backend;
using testing::load_rd_system;

// A square patch of 1 cm cells' scale (the models' units: common/reaction_diffusion/reaction_models.cpp).
json square(const std::string& model, json extra = json::object()) {
  json j = {{"mesh", "shape:square"}, {"scale_to_area", 0.09}, {"max_circumradius", 0.008},
            {"model", model},         {"time_step", 1.0},      {"seed", 5}};
  j.update(extra);
  return j;
}

const IntrinsicVertexData<double>& coefficient(const testing::LoadedReactionDiffusion& rd, const std::string& name) {
  const auto c = std::find(rd.system.coefficient_names.begin(), rd.system.coefficient_names.end(), name);
  return rd.system.coefficients[static_cast<size_t>(c - rd.system.coefficient_names.begin())];
}

TEST(AppendixModels, BetaNoiseIsUniformOverItsRangeAndFixedByTheSeed) {
  for (const auto& [model, mean] : {std::pair<std::string, double>{"turing-spots", 12.0}, {"meinhardt-spots", 1.0},
                                    {"meinhardt-stripes", 1.0}}) {
    const auto rd = load_rd_system(square(model));
    const auto& beta = coefficient(rd, "beta");
    const double n = static_cast<double>(beta.size());
    ASSERT_GT(n, 500.0);
    double sum = 0.0, low = 1e300, high = -1e300;
    for (const double b : beta) sum += b, low = std::min(low, b), high = std::max(high, b);
    // Uniform on [mean - 0.1, mean + 0.1]: every draw inside, the extremes near the ends (the chance
    // that none of n draws falls in the last 2 % of the range is 0.98^n < 1e-4 here), the mean within
    // 4 standard errors (0.1 / sqrt(3 n)).
    EXPECT_GE(low, mean - 0.1) << model;
    EXPECT_LE(high, mean + 0.1) << model;
    EXPECT_LT(low, mean - 0.096) << model;
    EXPECT_GT(high, mean + 0.096) << model;
    EXPECT_NEAR(sum / n, mean, 4 * 0.1 / std::sqrt(3 * n)) << model;
    // The other coefficients stay uniform.
    for (size_t c = 0; c < rd.system.coefficients.size(); ++c) {
      if (rd.system.coefficient_names[c] == "beta") continue;
      EXPECT_EQ(*std::min_element(rd.system.coefficients[c].begin(), rd.system.coefficients[c].end()),
                *std::max_element(rd.system.coefficients[c].begin(), rd.system.coefficients[c].end()))
          << model << " " << rd.system.coefficient_names[c];
    }
    // The same seed draws the same noise, another seed other noise; amplitude 0 none at all.
    EXPECT_EQ(coefficient(load_rd_system(square(model)), "beta").values(), beta.values()) << model;
    EXPECT_NE(coefficient(load_rd_system(square(model, {{"seed", 6}})), "beta").values(), beta.values()) << model;
    const auto quiet = load_rd_system(square(model, {{"parameter_noise", {{"beta", 0.0}}}}));
    for (const double b : coefficient(quiet, "beta")) ASSERT_EQ(b, mean) << model;
  }
}

// Meinhardt's stripe system, beta = 1 and no noise, started at its symmetric uniform steady state
// (a, b, c, d, e) = (0.75, 0.75, 0.140625, 0.75, 0.75) (derived in
// test_reaction_diffusion_scene.cpp): every morphogen stays there to 1e-6 on both backends.
TEST(AppendixModels, TheStripeSystemsUniformSteadyStateHoldsOnBothBackends) {
  const auto rd = load_rd_system(square("meinhardt-stripes", {{"parameter_noise", {{"beta", 0.0}}}}));
  const std::vector<double> state = {0.75, 0.75, 0.140625, 0.75, 0.75};
  for (const BackendChoice choice : {BackendChoice::Reference, BackendChoice::OpenCL}) {
    auto b = rd_backend(rd, choice);
    b->run(2000);
    for (int m = 0; m < 5; ++m) {
      double worst = 0.0;
      for (const double x : b->field_values(m)) worst = std::max(worst, std::abs(x - state[static_cast<size_t>(m)]));
      EXPECT_LT(worst, 1e-6) << to_string(choice) << " morphogen " << rd.system.morphogens[static_cast<size_t>(m)];
    }
  }
}


// The stripe system from its beta noise plus a small initial noise: the state moves, the OpenCL
// step (five morphogens: the wide vector) stays on the reference within float rounding, and the
// planted lane mix-up moves far off it.
TEST(AppendixModels, TheFiveMorphogenStepFollowsTheReferenceAndItsFaultDoesNot) {
  const auto rd = load_rd_system(square("meinhardt-stripes", {{"initial", {{"noise", 0.05}}}}));
  auto reference = rd_backend(rd, BackendChoice::Reference);
  auto device = rd_backend(rd, BackendChoice::OpenCL);
  auto mixed = rd_backend(rd, BackendChoice::OpenCL, "rd-lane-mixup");
  const auto a0 = reference->field_values(0);
  for (auto* b : {reference.get(), device.get(), mixed.get()}) b->run(200);
  double moved = 0.0;
  const auto a = reference->field_values(0);
  for (size_t i = 0; i < a.size(); ++i) moved = std::max(moved, std::abs(a[i] - a0[i]));
  EXPECT_GT(moved, 0.05);
  EXPECT_LT(largest_difference(*reference, *device), 1e-4);
  EXPECT_GT(largest_difference(*reference, *mixed), 1e-2);
}

}  // namespace
}  // namespace physarum
