// Short-time diffusion of a map (common/map_tools/surface_diffusion.hpp, the "diffuse" map source): it keeps
// the mass-weighted integral, never raises the maximum nor lowers the minimum, damps a first
// spherical harmonic at the rate backward Euler predicts (which fixes the time's units), composes
// with the other maps in a scene, and refuses bad times, step counts and operands.
#include "common/base/errors.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/map_tools/surface_diffusion.hpp"
#include "map_tool_meshes.hpp"
#include "mass_integral.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace physarum {
namespace {

using nlohmann::json;
using testing::evaluate_json;
using testing::mass_integral;
using testing::surface_from;

// A sharp-edged seed and a ramp times it, blurred in one and in several steps, step by step: the
// integral of m u stays (the columns of L sum to zero), and every step is a weighted average of the
// step before (M + h L is an M-matrix on the intrinsic Delaunay triangulation).
TEST(MapToolsDiffusion, ConservesTheIntegralAndNeverExceedsTheExtremes) {
  const PreparedSurface s = surface_from(testing::make_icosphere(3), 0.1);
  const EvaluatedMaps m = evaluate_json(
      {{"seed", {{"sphere", {{"center", {0.0, 0.0, 1.0}}, {"radius", 0.5}}}}},
       {"ramp", {{"axis", "x"}}},
       {"start", {{"sum", json::array({"seed", "ramp"})}}}},
      s);
  for (const std::string& name : {std::string("seed"), std::string("start")}) {
    IntrinsicVertexData<double> u = m.scalar_map(name);
    const double integral = mass_integral(s.domain, u);
    const BackwardEulerDiffusion diffusion(s.domain, 0.01);
    for (int step = 0; step < 5; ++step) {
      const IntrinsicVertexData<double> next = diffusion.step(u);
      EXPECT_NEAR(mass_integral(s.domain, next), integral, 1e-9 * std::abs(integral)) << name << " step " << step;
      EXPECT_LE(*std::max_element(next.begin(), next.end()), *std::max_element(u.begin(), u.end()) + 1e-12) << name;
      EXPECT_GE(*std::min_element(next.begin(), next.end()), *std::min_element(u.begin(), u.end()) - 1e-12) << name;
      // It does blur: the spread shrinks strictly.
      EXPECT_LT(*std::max_element(next.begin(), next.end()) - *std::min_element(next.begin(), next.end()),
                *std::max_element(u.begin(), u.end()) - *std::min_element(u.begin(), u.end()));
      u = next;
    }
    const IntrinsicVertexData<double> once = diffuse_on_surface(s.domain, m.scalar_map(name), 0.05, 5);
    for (int v = 0; v < s.domain.vertex_count; ++v) ASSERT_NEAR(once[v], u[v], 1e-12);
  }
}

// On the unit sphere z is an eigenfunction of the Laplace-Beltrami operator with eigenvalue 2, so a
// backward-Euler step of h multiplies it by 1 / (1 + 2h), and n steps over time T by
// (1 + 2T/n)^-n -> exp(-2T). The axis ramp (an affine function of z) keeps its mean and its z part
// shrinks by that factor (the discrete eigenvalue is 2 up to O(h^2)). Time is in the domain's m^2.
TEST(MapToolsDiffusion, DampsAFirstHarmonicAtTheBackwardEulerRate) {
  const PreparedSurface s = surface_from(testing::make_icosphere(4));
  const double T = 0.1;
  for (const int steps : {1, 4}) {
    const EvaluatedMaps m = evaluate_json(
        {{"height", {{"axis", "z"}}}, {"blur", {{"diffuse", "height"}, {"time", T}, {"steps", steps}}}}, s);
    // Fit blur - mean = k (z - mean) by least squares.
    const double mean_z = mass_integral(s.domain, m.scalar_map("height")) / s.domain.total_area;
    double zz = 0.0, zb = 0.0;
    for (int v = 0; v < s.domain.vertex_count; ++v) {
      const double a = m.scalar_map("height")[v] - mean_z, b = m.scalar_map("blur")[v] - mean_z;
      zz += s.domain.vertex_mass[v] * a * a, zb += s.domain.vertex_mass[v] * a * b;
    }
    const double expected = std::pow(1.0 + 2.0 * T / steps, -steps);
    EXPECT_NEAR(zb / zz, expected, 2e-3) << steps << " steps";
  }
}

// The composed example of the issue, in a whole scene: a blurred seed drives a parameter through a
// range, and the gradient of a Laplace map is the bias direction.
TEST(MapToolsDiffusion, ComposesWithOtherMapsInAScene) {
  testing::TempDir dir;
  const json scene = {
      {"mesh", "shape:square"}, {"agents", 200},         {"time_step", 0.02},
      {"sensor_angle", 22.5},   {"move_rate", 0.5},      {"turn_rate", 180.0},      {"turn_frequency", 20.0},
      {"deposit_rate", 1.0},    {"decay_rate", 1.0},     {"diffuse_rate", 0.0002},  {"mean_lifetime", 1.0},
      {"maps",
       {{"seed", {{"sphere", {{"center", {0.5, 0.5, 0.0}}, {"radius", 0.1}}}}},
        {"scale", {{"diffuse", "seed"}, {"time", 0.01}}},
        {"left", {{"box", {{"min", {-1.0, -1.0, -1.0}}, {"max", {0.01, 2.0, 1.0}}}}}},
        {"between", {{"laplace", json::array({{{"region", "left"}, {"value", 0.0}}, {{"region", "seed"}, {"value", 1.0}}})}}},
        {"toward_seed", {{"gradient", "between"}, {"normalize", true}}}}},
      {"sensor_distance", {{"map", "scale"}, {"range", {0.03, 0.08}}}},
      {"bias", {{"direction", "toward_seed"}, {"strength", 40.0}}}};
  const std::string path = (dir.path / "scene.json").string();
  std::ofstream(path) << scene.dump(2);
  const Scene loaded = load_scene(path);
  const PreparedSurface surface = prepare_scene_surface(loaded);
  const SceneArrays arrays = scene_arrays(loaded, surface);
  const EvaluatedMaps maps = evaluate_maps(loaded.maps, surface, path);
  const IntrinsicVertexData<double>& scale = maps.scalar_map("scale");
  for (int v = 0; v < surface.domain.vertex_count; ++v) {
    EXPECT_GT(scale[v], 0.0);  // the blur reaches everywhere (a backward-Euler step is global)
    EXPECT_LT(scale[v], 1.0);
    EXPECT_NEAR(arrays.parameters[Param::sensor_distance][v], 0.03 + 0.05 * scale[v], 1e-15);
  }
  ASSERT_TRUE(arrays.controls.bias.has_value());
  EXPECT_EQ(arrays.controls.bias->direction, maps.vector_map("toward_seed"));
}

TEST(MapToolsDiffusion, BadDiffusionsAreRefusedNamingTheMap) {
  auto error_of = [](const json& maps) { return testing::input_error_of([&] { parse_maps(maps, ".", "scene.json"); }); };
  std::string e = error_of({{"seed", 1.0}, {"blur", {{"diffuse", "seed"}, {"time", 0.0}}}});
  EXPECT_NE(e.find("scene.json: key 'maps': map 'blur': \"time\" = 0.0 must be > 0"), std::string::npos) << e;
  e = error_of({{"seed", 1.0}, {"blur", {{"diffuse", "seed"}, {"time", -1}}}});
  EXPECT_NE(e.find("\"time\" = -1 must be > 0"), std::string::npos) << e;
  e = error_of({{"seed", 1.0}, {"blur", {{"diffuse", "seed"}}}});
  EXPECT_NE(e.find("map 'blur': missing \"time\""), std::string::npos) << e;
  e = error_of({{"seed", 1.0}, {"blur", {{"diffuse", "seed"}, {"time", 0.1}, {"steps", 0}}}});
  EXPECT_NE(e.find("\"steps\" = 0 must be a whole number from 1"), std::string::npos) << e;
  e = error_of({{"seed", 1.0}, {"blur", {{"diffuse", "seed"}, {"time", 0.1}, {"steps", 2.5}}}});
  EXPECT_NE(e.find("\"steps\" = 2.5 must be a whole number"), std::string::npos) << e;
  e = error_of({{"east", {{"direction", {1.0, 0.0, 0.0}}}}, {"blur", {{"diffuse", "east"}, {"time", 0.1}}}});
  EXPECT_NE(e.find("map 'blur': reads map 'east', a vector map, where a scalar map is needed"), std::string::npos) << e;
  e = error_of({{"blur", {{"diffuse", "seed"}, {"time", 0.1}}}});
  EXPECT_NE(e.find("map 'blur': reads map 'seed', which is not defined"), std::string::npos) << e;
  e = error_of({{"seed", 1.0}, {"blur", {{"diffuse", "seed"}, {"time", 0.1}, {"method", "heat"}}}});
  EXPECT_NE(e.find("unknown field \"method\""), std::string::npos) << e;

  // The library function refuses the same, for callers that do not come through a scene.
  const PreparedSurface s = surface_from(testing::make_flat_rectangle(0.0, 1.0, 0.0, 1.0, 4, 4));
  const IntrinsicVertexData<double> u(static_cast<size_t>(s.domain.vertex_count), 1.0);
  EXPECT_NE(testing::input_error_of([&] { diffuse_on_surface(s.domain, u, 0.0); }).find("must be a positive finite time"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([&] { diffuse_on_surface(s.domain, u, 0.1, 0); }).find("\"steps\" = 0 must be at least 1"),
            std::string::npos);
}

}  // namespace
}  // namespace physarum
