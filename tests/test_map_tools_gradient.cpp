// Finite-element gradients as maps (common/map_tools/surface_gradient.hpp, the "gradient" and "slope" map
// sources): the gradient of a linear function is exact on every face, in the face's own frame and in
// the domain's units; normalised it has unit length, and zero where the map is flat; written back
// onto the input it is the same vector in input coordinates; the slope is its length.
#include "common/base/errors.hpp"
#include "common/map_tools/surface_gradient.hpp"
#include "map_tool_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;
using testing::evaluate_json;
using testing::intrinsic_vertex_positions;
using testing::surface_from;

// u = 2x - 5y on the unit square (jittered, refined, scaled to 4 m^2 so lengths double): in scene
// metres grad u = (2, -5) / 2. Face frame of face T: x along corner 0 -> corner 1, y its
// counter-clockwise perpendicular (surface_domain.hpp); computed here from the corners' input
// positions, so the expected vector does not come from the code under test.
TEST(MapToolsGradient, GradientOfALinearFunctionIsExactOnEveryFace) {
  const PreparedSurface s = surface_from(testing::make_flat_rectangle(0.0, 1.0, 0.0, 1.0, 10, 10, 0.3), 0.03, 4.0);
  ASSERT_GT(s.domain.vertex_count, s.input.vertex_count());
  const json maps = {{"ramp_x", {{"axis", "x"}}},
                     {"ramp_y", {{"axis", "y"}}},
                     {"two_x", {{"map", "ramp_x"}, {"range", {0.0, 2.0}}}},
                     {"minus_five_y", {{"map", "ramp_y"}, {"range", {0.0, -5.0}}}},
                     {"u", {{"sum", {"two_x", "minus_five_y"}}}},
                     {"raw", {{"gradient", "u"}}},
                     {"unit", {{"gradient", "u"}, {"normalize", true}}},
                     {"steep", {{"slope", "u"}}}};
  const EvaluatedMaps m = evaluate_json(maps, s);
  const std::vector<Eigen::Vector3d> p = intrinsic_vertex_positions(s);
  const Eigen::Vector3d gradient_in_scene_units(1.0, -2.5, 0.0);
  for (int f = 0; f < s.domain.face_count; ++f) {
    const std::array<int, 3>& v = s.domain.face_vertices[f];
    const Eigen::Vector3d x_axis = (p[v[1]] - p[v[0]]).normalized();
    const Eigen::Vector3d y_axis = Eigen::Vector3d::UnitZ().cross(x_axis);
    const Eigen::Vector2d expected(gradient_in_scene_units.dot(x_axis), gradient_in_scene_units.dot(y_axis));
    const auto& raw = m.vector_map("raw")[f];
    // Exact up to rounding: the face frames are laid out from intrinsic edge lengths, whose
    // relative rounding the gradient divides by the face's height (~1e-2 here).
    ASSERT_NEAR(raw[0], expected.x(), 1e-8) << f;
    ASSERT_NEAR(raw[1], expected.y(), 1e-8) << f;
    const auto& unit = m.vector_map("unit")[f];
    ASSERT_NEAR(unit[0], expected.normalized().x(), 1e-8) << f;
    ASSERT_NEAR(unit[1], expected.normalized().y(), 1e-8) << f;
  }
  for (int v = 0; v < s.domain.vertex_count; ++v) ASSERT_NEAR(m.scalar_map("steep")[v], std::sqrt(29.0) / 2.0, 1e-9) << v;

  // Written back onto the input: per input triangle, in input coordinates (per input unit).
  const MapSet set = parse_maps(maps, ".", "scene.json");
  const InputMaps on_input = maps_on_input(set, s, m, "scene.json");
  ASSERT_EQ(on_input.vector.size(), 2u);
  for (const auto& [name, vectors] : on_input.vector) {
    ASSERT_EQ(static_cast<int>(vectors.size()), s.input.triangle_count());
    const Eigen::Vector3d expected = name == "raw" ? Eigen::Vector3d(2.0, -5.0, 0.0) : Eigen::Vector3d(2.0, -5.0, 0.0).normalized();
    for (const Eigen::Vector3d& g : vectors) ASSERT_LT((g - expected).norm(), 1e-9) << name;
  }
}

// On a curved surface the gradient lies in each face: the gradient of the height z on the unit
// sphere has length sin(polar angle) = sqrt(1 - z^2) (the tangential part of e_z), to the
// discretisation's accuracy, and normalised it has length 1.
TEST(MapToolsGradient, GradientOfHeightOnASphereHasTheTangentialLength) {
  const PreparedSurface s = surface_from(testing::make_icosphere(4));
  const EvaluatedMaps m = evaluate_json(
      {{"h", {{"axis", "z"}}}, {"g", {{"gradient", "h"}}}, {"n", {{"gradient", "h"}, {"normalize", true}}}}, s);
  const std::vector<Eigen::Vector3d> p = intrinsic_vertex_positions(s);
  // The axis ramp maps the input's z range to [0, 1].
  double low = 0.0, high = 0.0;
  for (const Eigen::Vector3d& q : s.input.positions) low = std::min(low, q.z()), high = std::max(high, q.z());
  double worst = 0.0;
  for (int f = 0; f < s.domain.face_count; ++f) {
    const std::array<int, 3>& v = s.domain.face_vertices[f];
    const Eigen::Vector3d centre = ((p[v[0]] + p[v[1]] + p[v[2]]) / 3.0).normalized();
    const double expected = std::sqrt(std::max(0.0, 1.0 - centre.z() * centre.z())) / (high - low);
    const auto& g = m.vector_map("g")[f];
    worst = std::max(worst, std::abs(std::hypot(g[0], g[1]) - expected));
    const auto& n = m.vector_map("n")[f];
    ASSERT_NEAR(std::hypot(n[0], n[1]), 1.0, 1e-12) << f;
  }
  EXPECT_LT(worst, 0.01);  // edge length ~0.06: the chordal error is O(h^2)
}

// Where the map is flat there is no direction: the normalised gradient is the zero vector (the
// bias reads it as "no bias here"), never a NaN.
TEST(MapToolsGradient, NormalisedGradientOfAFlatMapIsZero) {
  const PreparedSurface s = surface_from(testing::make_flat_rectangle(0.0, 1.0, 0.0, 1.0, 6, 6));
  const EvaluatedMaps m = evaluate_json({{"one", 1.0}, {"flat", {{"gradient", "one"}, {"normalize", true}}}}, s);
  for (int f = 0; f < s.domain.face_count; ++f) {
    EXPECT_EQ(m.vector_map("flat")[f][0], 0.0);
    EXPECT_EQ(m.vector_map("flat")[f][1], 0.0);
  }
}

TEST(MapToolsGradient, BadGradientsAreRefusedNamingTheMap) {
  auto error_of = [](const json& maps) { return testing::input_error_of([&] { parse_maps(maps, ".", "scene.json"); }); };
  std::string e = error_of({{"g", {{"gradient", 2.0}}}});
  EXPECT_NE(e.find("map 'g': \"gradient\" = 2.0 must be a scalar map"), std::string::npos) << e;
  e = error_of({{"east", {{"direction", {1.0, 0.0, 0.0}}}}, {"g", {{"gradient", "east"}}}});
  EXPECT_NE(e.find("map 'g': reads map 'east', a vector map, where a scalar map is needed"), std::string::npos) << e;
  e = error_of({{"h", 1.0}, {"g", {{"gradient", "h"}, {"normalize", "yes"}}}});
  EXPECT_NE(e.find("\"normalize\" = \"yes\" must be true or false"), std::string::npos) << e;
  e = error_of({{"h", 1.0}, {"g", {{"gradient", "h"}, {"normalise", true}}}});
  EXPECT_NE(e.find("unknown field \"normalise\""), std::string::npos) << e;
  // A gradient is a vector map: it cannot be read where a scalar is needed.
  e = error_of({{"h", 1.0}, {"g", {{"gradient", "h"}}}, {"back", {{"invert", "g"}}}});
  EXPECT_NE(e.find("map 'back': reads map 'g', a vector map"), std::string::npos) << e;
  e = error_of({{"east", {{"direction", {1.0, 0.0, 0.0}}}}, {"s", {{"slope", "east"}}}});
  EXPECT_NE(e.find("map 's': reads map 'east', a vector map"), std::string::npos) << e;
  // Its components would clash with a map of that name in maps.ply.
  e = error_of({{"h", 1.0}, {"g", {{"gradient", "h"}}}, {"g_x", 1.0}});
  EXPECT_NE(e.find("the name is taken by the component g_x"), std::string::npos) << e;
}

}  // namespace
}  // namespace physarum
