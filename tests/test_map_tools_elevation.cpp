// The elevation proxy (common/map_tools/elevation_proxy.hpp, the "elevation" map source): a sphere has no
// relief, a sphere with bumps is higher on every bump than in every valley, a height field is highest
// at its peak, the smoothed copy keeps the enclosed volume, the result does not depend on the
// mesh's units, and bad settings are refused.
#include "common/map_tools/elevation_proxy.hpp"
#include "common/base/errors.hpp"
#include "map_tool_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;
using testing::evaluate_json;
using testing::surface_from;

// Five bumps around the equator: Re((x + iy)^5) = sin^5(polar) cos(5 azimuth), +1 on the bumps'
// tops, -1 in the valleys between them, 0 at the poles.
double five_bumps(const Eigen::Vector3d& p) {
  const double x = p.x(), y = p.y();
  return x * x * x * x * x - 10.0 * x * x * x * y * y + 5.0 * x * y * y * y * y;
}

// On a sphere every point is as high as every other: what is left of d is the discretisation's
// noise (the icosphere's valence-5 vertices), far below the relief floor, so the map is 0.5 to within
// that noise over the floor.
TEST(MapToolsElevation, ASphereHasNoRelief) {
  const InputMesh sphere = testing::make_icosphere(4);
  const ElevationProxy proxy = elevation_proxy(sphere, 0.01, 1, "test");
  const auto [low, high] = std::minmax_element(proxy.signed_distance.begin(), proxy.signed_distance.end());
  EXPECT_LT(*high - *low, 1e-3) << "relief of the unit sphere";
  for (int v = 0; v < sphere.vertex_count(); ++v) ASSERT_NEAR(proxy.value[v], 0.5, 0.15) << v;
}

TEST(MapToolsElevation, TheSmoothedCopyKeepsTheEnclosedVolume) {
  const InputMesh bumpy = testing::make_displaced_sphere(3, 0.1, five_bumps);
  for (const int steps : {1, 3}) {
    const ElevationProxy proxy = elevation_proxy(bumpy, 0.02, steps, "test");
    const double original = enclosed_volume(bumpy.positions, bumpy.triangles);
    EXPECT_NEAR(enclosed_volume(proxy.smoothed, bumpy.triangles), original, 1e-12 * original);
    // And it did smooth: the bumps are (mostly) gone from the copy.
    double copy_bumps = 0.0, input_bumps = 0.0;
    for (int v = 0; v < bumpy.vertex_count(); ++v) {
      const Eigen::Vector3d& p = bumpy.positions[static_cast<size_t>(v)];
      const double f = five_bumps(p.normalized());
      input_bumps += f * p.norm(), copy_bumps += f * proxy.smoothed[static_cast<size_t>(v)].norm();
    }
    EXPECT_LT(std::abs(copy_bumps), 0.5 * std::abs(input_bumps)) << steps;
  }
}

// Each closed component keeps its own volume about its own centre: a bumpy sphere and a plain
// sphere of radius 2 side by side, in one mesh.
TEST(MapToolsElevation, EachClosedComponentKeepsItsOwnVolume) {
  InputMesh two = testing::make_displaced_sphere(3, 0.1, five_bumps);
  const InputMesh big = testing::make_icosphere(3);
  const int offset = two.vertex_count();
  for (const Eigen::Vector3d& q : big.positions) two.positions.push_back(2.0 * q + Eigen::Vector3d(5.0, 0.0, 0.0));
  for (const auto& t : big.triangles) two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const ElevationProxy proxy = elevation_proxy(two, 0.002, 1, "test");
  const std::vector<std::array<int, 3>> first(two.triangles.begin(), two.triangles.begin() + (two.triangle_count() - big.triangle_count()));
  const std::vector<std::array<int, 3>> second(two.triangles.end() - big.triangle_count(), two.triangles.end());
  for (const auto* faces : {&first, &second}) {
    const double original = enclosed_volume(two.positions, *faces);
    EXPECT_NEAR(enclosed_volume(proxy.smoothed, *faces), original, 1e-12 * original);
  }
  // The plain sphere stays where it was: its copy's centre is its own.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int v = offset; v < two.vertex_count(); ++v) centre += proxy.smoothed[static_cast<size_t>(v)] / big.vertex_count();
  EXPECT_LT((centre - Eigen::Vector3d(5.0, 0.0, 0.0)).norm(), 1e-9);
}

// Bumps of 10 % of the radius: every vertex near a bump's top is higher than every vertex near a
// valley's bottom, and the relief spans exactly 0..1.
TEST(MapToolsElevation, BumpsAreHigherThanValleys) {
  const PreparedSurface s = surface_from(testing::make_displaced_sphere(4, 0.1, five_bumps));
  const EvaluatedMaps m = evaluate_json({{"height", {{"elevation", {{"time", 0.01}}}}}}, s);
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  double lowest_top = 1.0, highest_bottom = 0.0, low = 1.0, high = 0.0;
  int tops = 0, bottoms = 0;
  for (int v = 0; v < s.domain.vertex_count; ++v) {
    const double f = five_bumps(p[v].normalized()), e = m.scalar_map("height")[v];
    if (f > 0.8) lowest_top = std::min(lowest_top, e), ++tops;
    if (f < -0.8) highest_bottom = std::max(highest_bottom, e), ++bottoms;
    low = std::min(low, e), high = std::max(high, e);
  }
  ASSERT_GT(tops, 10);
  ASSERT_GT(bottoms, 10);
  EXPECT_GT(lowest_top, highest_bottom + 0.3) << "tops from " << lowest_top << ", bottoms up to " << highest_bottom;
  EXPECT_DOUBLE_EQ(low, 0.0);
  EXPECT_DOUBLE_EQ(high, 1.0);
}

// An open surface keeps its boundary in place: a flat square stays flat (d = 0 everywhere: exactly
// 0.5), and a square with a round hill in its middle is highest at the hill's top.
TEST(MapToolsElevation, AnOpenHeightFieldIsHighestAtItsPeak) {
  InputMesh flat = testing::make_flat_rectangle(0.0, 1.0, 0.0, 1.0, 20, 20, 0.2);
  const ElevationProxy level = elevation_proxy(flat, 0.01, 1, "test");
  for (int v = 0; v < flat.vertex_count(); ++v) ASSERT_EQ(level.value[v], 0.5) << v;

  InputMesh hill = flat;
  for (Eigen::Vector3d& q : hill.positions) q.z() = 0.1 * std::exp(-((q - Eigen::Vector3d(0.5, 0.5, 0.0)).squaredNorm()) / 0.01);
  const ElevationProxy proxy = elevation_proxy(hill, 0.01, 1, "test");
  const int peak = static_cast<int>(std::max_element(hill.positions.begin(), hill.positions.end(),
                                                     [](const auto& a, const auto& b) { return a.z() < b.z(); }) -
                                    hill.positions.begin());
  EXPECT_EQ(proxy.value[peak], 1.0);
  for (int v = 0; v < hill.vertex_count(); ++v) {
    const Eigen::Vector3d& q = hill.positions[static_cast<size_t>(v)];
    const bool boundary = q.x() == 0.0 || q.x() == 1.0 || q.y() == 0.0 || q.y() == 1.0;
    if (boundary) {
      EXPECT_EQ(proxy.smoothed[static_cast<size_t>(v)], q) << "boundary vertices are held";
      EXPECT_LT(proxy.value[v], proxy.value[peak] - 0.5);
    }
  }
}

// Time is a fraction of the squared bounding-box diagonal: the same mesh in other units (x 100)
// gives the same map.
TEST(MapToolsElevation, DoesNotDependOnTheMeshUnits) {
  const InputMesh bumpy = testing::make_displaced_sphere(3, 0.1, five_bumps);
  InputMesh in_centimetres = bumpy;
  for (Eigen::Vector3d& q : in_centimetres.positions) q *= 100.0;
  const ElevationProxy a = elevation_proxy(bumpy, 0.005, 2, "test"), b = elevation_proxy(in_centimetres, 0.005, 2, "test");
  for (int v = 0; v < bumpy.vertex_count(); ++v) {
    ASSERT_NEAR(a.value[v], b.value[v], 1e-9) << v;
    ASSERT_NEAR(100.0 * a.signed_distance[v], b.signed_distance[v], 1e-9 * 100.0) << v;
  }
}

// The map on the intrinsic vertices is the input's proxy carried through their input locations:
// exactly the input's value on the intrinsic vertices that are input vertices, and in between
// elsewhere; "slope" composes with it.
TEST(MapToolsElevation, ReachesIntrinsicVerticesThroughTheirInputLocations) {
  const InputMesh bumpy = testing::make_displaced_sphere(2, 0.1, five_bumps);
  const PreparedSurface s = surface_from(bumpy, 0.1);
  ASSERT_GT(s.domain.vertex_count, s.input.vertex_count());
  const EvaluatedMaps m = evaluate_json({{"height", {{"elevation", {{"time", 0.01}}}}}, {"steep", {{"slope", "height"}}}}, s);
  const ElevationProxy proxy = elevation_proxy(bumpy, 0.01, 1, "test");
  for (int v = 0; v < s.input.vertex_count(); ++v) EXPECT_EQ(m.scalar_map("height")[s.input_to_intrinsic[v]], proxy.value[v]);
  for (int v = 0; v < s.domain.vertex_count; ++v) {
    const SurfacePoint& l = s.domain.vertex_location[v];
    const auto& t = s.input.triangles[static_cast<size_t>(l.face)];
    const double expected = l.barycentric[0] * proxy.value[t[0]] + l.barycentric[1] * proxy.value[t[1]] + l.barycentric[2] * proxy.value[t[2]];
    ASSERT_NEAR(m.scalar_map("height")[v], expected, 1e-12) << v;
    ASSERT_GE(m.scalar_map("steep")[v], 0.0);
  }
}

TEST(MapToolsElevation, BadSettingsAreRefusedNamingTheMap) {
  auto error_of = [](const json& maps) { return testing::input_error_of([&] { parse_maps(maps, ".", "scene.json"); }); };
  std::string e = error_of({{"h", {{"elevation", {{"time", 0}}}}}});
  EXPECT_NE(e.find("map 'h': \"time\" = 0 must be > 0"), std::string::npos) << e;
  e = error_of({{"h", {{"elevation", {{"time", -0.1}}}}}});
  EXPECT_NE(e.find("must be > 0"), std::string::npos) << e;
  e = error_of({{"h", {{"elevation", 0.05}}}});
  EXPECT_NE(e.find("map 'h': \"elevation\" = 0.05 must be an object"), std::string::npos) << e;
  e = error_of({{"h", {{"elevation", {{"time", 0.05}, {"volume", true}}}}}});
  EXPECT_NE(e.find("unknown field \"volume\""), std::string::npos) << e;
  e = error_of({{"h", {{"elevation", {{"time", 0.05}, {"steps", -2}}}}}});
  EXPECT_NE(e.find("\"steps\" = -2 must be a whole number"), std::string::npos) << e;
  EXPECT_NE(testing::input_error_of([] { elevation_proxy(testing::make_icosphere(1), 0.0, 1, "here"); }).find("here: \"time\""),
            std::string::npos);
}

}  // namespace
}  // namespace physarum
