// Map definitions written inline where a map is expected (common/maps/inline_maps.hpp): each becomes a
// named map, named after where it was written, and the composed map is the same as the one spelled
// out with names — so the known answers of the map tools carry over. On the flat square the
// normalised gradient of the fast-marching distance from a corner points away from that corner.
#include "common/base/errors.hpp"
#include "common/maps/inline_maps.hpp"
#include "map_tool_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace physarum {
namespace {

using nlohmann::json;
using testing::evaluate_json;
using testing::surface_from;

TEST(InlineMaps, InlineDefinitionsBecomeNamedMapsNamedAfterWhereTheyWere) {
  const json given = json::parse(R"({
    "stem": {"sphere": {"center": [0, 0, 0], "radius": 0.1}},
    "toward_stem": {"gradient": {"geodesic_distance": {"from": {"sphere": {"center": [1, 1, 0], "radius": 0.1}}}},
                    "normalize": true},
    "mix": {"sum": [{"invert": "stem"}, 0.5, "stem"]},
    "toward_stem_gradient": 1.0
  })");
  const json named = with_inline_maps_named(given);
  // The user's own "toward_stem_gradient" keeps its name; the inline gradient operand takes "_2".
  EXPECT_EQ(named.at("toward_stem_gradient"), 1.0);
  EXPECT_EQ(named.at("toward_stem").at("gradient"), "toward_stem_gradient_2");
  EXPECT_EQ(named.at("toward_stem_gradient_2").at("geodesic_distance").at("from"), "toward_stem_gradient_2_from");
  EXPECT_TRUE(named.at("toward_stem_gradient_2_from").contains("sphere"));
  EXPECT_EQ(named.at("mix").at("sum"), json::parse(R"(["mix_sum_0", 0.5, "stem"])"));
  EXPECT_EQ(named.at("mix_sum_0"), json::parse(R"({"invert": "stem"})"));
  EXPECT_EQ(named.size(), given.size() + 3);
}

TEST(InlineMaps, SeedSetsStayWhereTheyAre) {
  const json given = json::parse(R"({
    "d": {"geodesic_distance": {"from": {"points": [[0, 0, 0]]}}},
    "e": {"geodesic_distance": {"from": {"boundary": {"spacing": 0.2}}}},
    "h": {"laplace": [{"region": {"box": {"min": [0, 0, -1], "max": [0.1, 1, 1]}}, "value": 1},
                      {"region": "d", "value": 0}]}
  })");
  const json named = with_inline_maps_named(given);
  EXPECT_EQ(named.at("d"), given.at("d"));
  EXPECT_EQ(named.at("e"), given.at("e"));
  EXPECT_EQ(named.at("h").at("laplace")[0].at("region"), "h_region_0");
  EXPECT_EQ(named.at("h").at("laplace")[1].at("region"), "d");
}

// The composition of the issue's example, evaluated: inline and named give the same values, and on
// the flat square the normalised gradient of the fast-marching distance from the corner (0, 0) is
// the unit vector away from the corner (the distance is Euclidean there).
TEST(InlineMaps, AComposedMapEqualsTheSameMapSpelledOutWithNames) {
  const PreparedSurface s = surface_from(testing::make_flat_rectangle(0.0, 1.0, 0.0, 1.0, 16, 16, 0.2));
  const json corner = json::parse(R"({"sphere": {"center": [0, 0, 0], "radius": 0.01}})");
  const EvaluatedMaps inline_maps = evaluate_json(
      {{"corner", corner},
       {"away", {{"gradient", {{"geodesic_distance", {{"from", "corner"}, {"method", "fmm"}}}}}, {"normalize", true}}}},
      s);
  const EvaluatedMaps named_maps = evaluate_json({{"corner", corner},
                                                  {"dist", {{"geodesic_distance", {{"from", "corner"}, {"method", "fmm"}}}}},
                                                  {"away", {{"gradient", "dist"}, {"normalize", true}}}},
                                                 s);
  const auto& a = inline_maps.vector_map("away");
  const auto& b = named_maps.vector_map("away");
  ASSERT_EQ(a.size(), b.size());
  const auto positions = testing::intrinsic_vertex_positions(s);
  int checked = 0;
  double worst = 0.0, sum = 0.0;
  for (int f = 0; f < s.domain.face_count; ++f) {
    ASSERT_EQ(a[f], b[f]) << f;
    // The face's frame: x from corner 0 to corner 1, y its counter-clockwise perpendicular.
    const auto& v = s.domain.face_vertices[f];
    const Eigen::Vector3d p0 = positions[v[0]], p1 = positions[v[1]];
    const Eigen::Vector3d centre = (p0 + p1 + positions[v[2]]) / 3.0;
    if (centre.head<2>().norm() < 0.2) continue;  // near the source the update is least accurate
    const Eigen::Vector3d ex = (p1 - p0).normalized();
    const Eigen::Vector3d ey = Eigen::Vector3d::UnitZ().cross(ex);
    const Eigen::Vector3d expected = Eigen::Vector3d(centre.x(), centre.y(), 0.0).normalized();
    const double angle = std::atan2(a[f][1], a[f][0]) - std::atan2(expected.dot(ey), expected.dot(ex));
    const double error = std::abs(std::remainder(angle, 2.0 * std::numbers::pi));
    worst = std::max(worst, error);
    sum += error;
    ++checked;
  }
  ASSERT_GT(checked, s.domain.face_count / 2);
  // First-order fast marching on a jittered 16 x 16 grid: a few degrees at worst, under a degree on
  // average (a gradient pointing the wrong way would be off by pi).
  EXPECT_LT(sum / checked, 0.02);  // measured 0.011 rad
  EXPECT_LT(worst, 0.08);            // measured 0.047 rad
}

TEST(InlineMaps, AnErrorInsideAnInlineMapNamesWhereItWas) {
  const std::string e = testing::input_error_of([] {
    parse_maps(json::parse(R"({"g": {"gradient": {"invert": "nowhere"}}})"), ".", "scene.json");
  });
  EXPECT_NE(e.find("map 'g_gradient': reads map 'nowhere', which is not defined"), std::string::npos) << e;
  const std::string v = testing::input_error_of([] {
    parse_maps(json::parse(R"({"s": {"slope": {"gradient": {"axis": "x"}}}})"), ".", "scene.json");
  });
  EXPECT_NE(v.find("map 's': reads map 's_slope', a vector map"), std::string::npos) << v;
}

}  // namespace
}  // namespace physarum
