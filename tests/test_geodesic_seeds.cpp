// Seed sets (common/map_tools/seed_set.hpp) and the geodesic_distance map source (common/map_tools/geodesic_distance.hpp
// through common/maps/map_definition + map_evaluation): points snap to the nearest vertex, regions are
// their vertices >= 0.5, the boundary is every boundary vertex or one every `spacing` metres of the
// scaled surface; a scene's geodesic_distance maps parse, order after the maps they read, and
// evaluate to the known distances; every bad seed set is refused with a message saying what and where.
#include "common/base/errors.hpp"
#include "common/maps/map_definition.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/map_tools/seed_set.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace physarum {
namespace {

using nlohmann::json;
using testing::input_error_of;

struct Prepared {
  PreparedSurface surface;
  std::vector<Eigen::Vector3d> position;  // intrinsic vertices in input coordinates
  std::map<std::string, IntrinsicVertexData<double>> maps;

  explicit Prepared(PreparedSurface s) : surface(std::move(s)) {
    for (int v = 0; v < surface.domain.vertex_count; ++v) {
      const SurfacePoint& l = surface.domain.vertex_location[v];
      const auto& t = surface.input.triangles[static_cast<size_t>(l.face)];
      position.push_back(l.barycentric[0] * surface.input.positions[t[0]] + l.barycentric[1] * surface.input.positions[t[1]] +
                         l.barycentric[2] * surface.input.positions[t[2]]);
    }
  }
  std::vector<int> seeds(const json& value) {
    const SeedSurface s{surface.domain, position, [&](const std::string& name) -> const IntrinsicVertexData<double>& {
                          return maps.at(name);
                        }};
    return seed_vertices(parse_seed_set(value, "test"), s, "test");
  }
};

// The unit square scaled to 4 m^2 (side 2 m): 33 x 33 vertices, 0.0625 m apart after scaling.
Prepared square() { return Prepared(prepare_surface(SurfaceSpec{"shape:square", 4.0, std::nullopt, 0.0})); }

TEST(SeedSet, PointsSnapToTheNearestVertexInInputCoordinates) {
  Prepared p = square();
  // (0.51, 0.26) in input coordinates is nearest to the grid vertex (0.5, 0.25) (cells of 1/32).
  const std::vector<int> seeds = p.seeds({{"points", {{0.51, 0.26, 0.0}, {0.0, 0.0, 0.3}}}});
  ASSERT_EQ(seeds.size(), 2u);
  std::set<std::pair<double, double>> at;
  for (const int v : seeds) at.emplace(p.position[static_cast<size_t>(v)].x(), p.position[static_cast<size_t>(v)].y());
  EXPECT_TRUE(at.count({0.5, 0.25}));
  EXPECT_TRUE(at.count({0.0, 0.0}));
}

TEST(SeedSet, ARegionIsItsVerticesAtOrAboveOneHalf) {
  Prepared p = square();
  IntrinsicVertexData<double> values(static_cast<size_t>(p.surface.domain.vertex_count), 0.0);
  std::set<int> expected;
  for (int v = 0; v < p.surface.domain.vertex_count; ++v) {
    values[static_cast<size_t>(v)] = p.position[static_cast<size_t>(v)].x();  // x in input units, 0..1
    if (p.position[static_cast<size_t>(v)].x() >= 0.5) expected.insert(v);
  }
  p.maps.emplace("east_half", values);
  const std::vector<int> seeds = p.seeds("east_half");
  EXPECT_EQ(std::set<int>(seeds.begin(), seeds.end()), expected);
  EXPECT_EQ(seeds.size(), 17u * 33u);  // columns x = 16/32 .. 32/32
}

TEST(SeedSet, BoundaryIsEveryBoundaryVertex) {
  Prepared p = square();
  const std::vector<int> seeds = p.seeds({{"boundary", true}});
  EXPECT_EQ(seeds.size(), 4u * 32u);
  for (const int v : seeds) {
    const Eigen::Vector3d& x = p.position[static_cast<size_t>(v)];
    EXPECT_TRUE(x.x() == 0.0 || x.x() == 1.0 || x.y() == 0.0 || x.y() == 1.0) << x.transpose();
  }
}

TEST(SeedSet, BoundarySpacingIsInScaledMetres) {
  Prepared p = square();
  // The scaled boundary is 8 m long: a seed every 0.5 m is 16 seeds, at every 8th boundary vertex,
  // i.e. at input coordinates that are multiples of 0.25 along the edges.
  const std::vector<int> seeds = p.seeds({{"boundary", {{"spacing", 0.5}}}});
  ASSERT_EQ(seeds.size(), 16u);
  for (const int v : seeds) {
    const Eigen::Vector3d& x = p.position[static_cast<size_t>(v)];
    EXPECT_NEAR(std::remainder(x.x(), 0.25), 0.0, 1e-12) << x.transpose();
    EXPECT_NEAR(std::remainder(x.y(), 0.25), 0.0, 1e-12) << x.transpose();
  }
  // A spacing longer than the boundary still seeds every loop once.
  EXPECT_EQ(p.seeds({{"boundary", {{"spacing", 100.0}}}}).size(), 1u);
}

TEST(SeedSet, BadSeedSetsAreRefusedSayingWhatAndWhere) {
  Prepared p = square();
  p.maps.emplace("nothing", IntrinsicVertexData<double>(static_cast<size_t>(p.surface.domain.vertex_count), 0.25));
  EXPECT_NE(input_error_of([&] { p.seeds("nothing"); }).find("test: the region 'nothing' holds no intrinsic vertex"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { p.seeds({{"points", json::array()}}); }).find("non-empty list"), std::string::npos);
  EXPECT_NE(input_error_of([&] { p.seeds({{"points", {{1.0, 2.0}}}}); }).find("\"points\"[0]"), std::string::npos);
  EXPECT_NE(input_error_of([&] { p.seeds({{"boundary", {{"spacing", 0.0}}}}); }).find("must be a number > 0"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { p.seeds({{"boundary", {{"spacing", -1.0}}}}); }).find("must be a number > 0"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { p.seeds({{"boundary", false}}); }).find("must be true"), std::string::npos);
  EXPECT_NE(input_error_of([&] { p.seeds({{"vertex", 3}}); }).find("is no seed set"), std::string::npos);
  Prepared sphere(prepare_surface(SurfaceSpec{"shape:sphere", std::nullopt, std::nullopt, 0.0}));
  EXPECT_NE(input_error_of([&] { sphere.seeds({{"boundary", true}}); }).find("closed surface"), std::string::npos);
}

// ---- the map source in a scene ------------------------------------------------------------------

EvaluatedMaps evaluate(const json& maps, const PreparedSurface& surface) {
  return evaluate_maps(parse_maps(maps, ".", "scene.json"), surface, "scene.json");
}

TEST(GeodesicDistanceMap, ParsesOrdersAndEvaluatesInAScene) {
  const Prepared p = square();
  // "from_corner" reads "corner", defined after it in the file; both methods; options inside and beside.
  const json maps = json::parse(R"({
      "heat_from_corner": {"geodesic_distance": {"from": "corner"}, "method": "heat"},
      "fmm_from_corner": {"geodesic_distance": {"from": "corner", "method": "fmm"}},
      "heat_wide": {"geodesic_distance": {"from": "corner"}, "time_factor": 4.0},
      "from_points": {"geodesic_distance": {"from": {"points": [[1.0, 1.0, 0.0]]}}, "method": "fmm"},
      "corner": {"sphere": {"center": [0.0, 0.0, 0.0], "radius": 0.01}}
  })");
  const MapSet set = parse_maps(maps, ".", "scene.json");
  const auto& order = set.in_dependency_order();
  auto index = [&](const std::string& name) {
    return std::find_if(order.begin(), order.end(), [&](const MapDefinition& m) { return m.name == name; }) - order.begin();
  };
  EXPECT_LT(index("corner"), index("heat_from_corner"));
  const EvaluatedMaps m = evaluate_maps(set, p.surface, "scene.json");
  // Distances in scaled metres: the square's side is 2 m, so a vertex at input (x, y) is 2|(x, y)|
  // from the corner and 2|(1 - x, 1 - y)| from the opposite one.
  for (int v = 0; v < p.surface.domain.vertex_count; ++v) {
    const Eigen::Vector3d& x = p.position[static_cast<size_t>(v)];
    const double exact = 2.0 * x.norm(), from_far = 2.0 * (Eigen::Vector3d(1.0, 1.0, 0.0) - x).norm();
    EXPECT_NEAR(m.scalar_map("fmm_from_corner")[static_cast<size_t>(v)], exact, 1e-3 * std::max(exact, 1e-9));
    EXPECT_NEAR(m.scalar_map("from_points")[static_cast<size_t>(v)], from_far, 1e-3 * std::max(from_far, 1e-9));
    EXPECT_NEAR(m.scalar_map("heat_from_corner")[static_cast<size_t>(v)], exact, 0.025 * 2.0 * std::sqrt(2.0));
    EXPECT_NEAR(m.scalar_map("heat_wide")[static_cast<size_t>(v)], exact, 0.05 * 2.0 * std::sqrt(2.0));
  }
}

TEST(GeodesicDistanceMap, BadDefinitionsAreRefusedNamingTheMap) {
  const PreparedSurface sphere = prepare_surface(SurfaceSpec{"shape:sphere", std::nullopt, std::nullopt, 0.0});
  auto parse_error = [](const char* maps) {
    return input_error_of([&] { parse_maps(json::parse(maps), ".", "scene.json"); });
  };
  auto has = [](const std::string& message, const char* part) {
    return message.find(part) != std::string::npos ? ::testing::AssertionSuccess()
                                                  : ::testing::AssertionFailure() << "'" << part << "' not in: " << message;
  };
  EXPECT_TRUE(has(parse_error(R"({"d": {"geodesic_distance": {"from": "r"}, "method": "dijkstra"}, "r": {"axis": "x"}})"),
                  "scene.json: key 'maps': map 'd': \"method\""));
  EXPECT_TRUE(has(parse_error(R"({"d": {"geodesic_distance": {"from": "r", "method": "fmm"}, "time_factor": 2}, "r": {"axis": "x"}})"),
                  "heat method only"));
  EXPECT_TRUE(has(parse_error(R"({"d": {"geodesic_distance": {"from": "r", "method": "fmm"}, "method": "fmm"}, "r": {"axis": "x"}})"),
                  "both inside and beside"));
  EXPECT_TRUE(has(parse_error(R"({"d": {"geodesic_distance": {"from": "r"}, "time_factor": 0}, "r": {"axis": "x"}})"),
                  "must be a number > 0"));
  EXPECT_TRUE(has(parse_error(R"({"d": {"geodesic_distance": {"from": "missing"}}})"), "reads map 'missing'"));
  EXPECT_TRUE(has(parse_error(R"({"d": {"geodesic_distance": {"to": "r"}}, "r": {"axis": "x"}})"), "\"from\""));
  EXPECT_TRUE(has(parse_error(R"({"d": {"geodesic_distance": {"from": {"boundary": {"spacing": -1}}}}})"),
                  "map 'd': \"from\": \"boundary\": \"spacing\" = -1 must be a number > 0"));
  // Evaluation-time errors name the map too.
  EXPECT_TRUE(has(input_error_of([&] { evaluate(json::parse(R"({"d": {"geodesic_distance": {"from": {"boundary": true}}}})"), sphere); }),
                  "scene.json: key 'maps': map 'd': \"from\": boundary seeds on a closed surface"));
  EXPECT_TRUE(has(input_error_of([&] {
                    evaluate(json::parse(R"({"d": {"geodesic_distance": {"from": "far"}},
                                             "far": {"sphere": {"center": [5, 5, 5], "radius": 0.1}}})"),
                             sphere);
                  }),
                  "map 'd': \"from\": the region 'far' holds no intrinsic vertex"));
}

}  // namespace
}  // namespace physarum
