// Laplace interpolation (common/map_tools/laplace_interpolation.hpp, the "laplace" map source): exact on a
// flat strip where the harmonic function is linear, converging at second order to the log profile
// on a flat annulus, within the regions' values everywhere, and every bad setup refused clearly.
#include "common/base/errors.hpp"
#include "common/map_tools/laplace_interpolation.hpp"
#include "map_tool_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;
using testing::evaluate_json;
using testing::intrinsic_vertex_positions;
using testing::surface_from;

// Between x = 0 (value 0) and x = 4 (value 1) on the strip [0, 4] x [0, 1], with natural conditions
// on the long sides, the harmonic function is x / 4, which piecewise-linear elements hold exactly
// (the cotan Laplacian annihilates linear functions, and their normal derivative on the long sides
// is zero). Jittered input vertices and intrinsic refinement (inserted vertices off the input's
// vertices) do not change that.
TEST(MapToolsLaplace, IsLinearBetweenTheShortSidesOfAFlatStrip) {
  const PreparedSurface s = surface_from(testing::make_flat_rectangle(0.0, 4.0, 0.0, 1.0, 24, 6, 0.3), 0.08);
  ASSERT_GT(s.domain.vertex_count, s.input.vertex_count());  // refinement inserted vertices
  const EvaluatedMaps m = evaluate_json(
      {{"left", {{"box", {{"min", {-1.0, -1.0, -1.0}}, {"max", {1e-9, 2.0, 1.0}}}}}},
       {"right", {{"half_space", {{"point", {4.0 - 1e-9, 0.0, 0.0}}, {"normal", {1.0, 0.0, 0.0}}}}}},
       {"between", {{"laplace", json::array({{{"region", "left"}, {"value", 0.0}}, {{"region", "right"}, {"value", 1.0}}})}}}},
      s);
  const std::vector<Eigen::Vector3d> p = intrinsic_vertex_positions(s);
  double worst = 0.0;
  for (int v = 0; v < s.domain.vertex_count; ++v) worst = std::max(worst, std::abs(m.scalar_map("between")[v] - p[v].x() / 4.0));
  EXPECT_LT(worst, 1e-9);
}

// u = log(r / a) / log(b / a) is harmonic on the annulus a <= r <= b with u = 0 on the inner circle
// and 1 on the outer. Linear elements converge at second order in the mesh size at the vertices:
// the fitted order over three refinements (h halved twice) is about 2. The rings are spaced 4 / N
// apart for N segments, so every triangle is acute (no flips change the pattern between
// refinements) and each refinement halves every edge.
TEST(MapToolsLaplace, MatchesTheLogProfileOnAFlatAnnulusAtSecondOrder) {
  const double a = 0.5, b = 1.0;
  const json maps = {
      {"inner", {{"sphere", {{"center", {0.0, 0.0, 0.0}}, {"radius", a + 1e-9}}}}},
      {"inside_outer", {{"sphere", {{"center", {0.0, 0.0, 0.0}}, {"radius", b - 1e-9}}}}},
      {"outer", {{"invert", "inside_outer"}}},
      {"profile", {{"laplace", json::array({{{"region", "inner"}, {"value", 0.0}}, {{"region", "outer"}, {"value", 1.0}}})}}}};
  std::vector<double> h, error;
  for (const int segments : {24, 48, 96}) {
    const PreparedSurface s = surface_from(testing::make_flat_annulus(a, b, segments, segments / 8));
    const EvaluatedMaps m = evaluate_json(maps, s);
    const std::vector<Eigen::Vector3d> p = intrinsic_vertex_positions(s);
    double worst = 0.0;
    for (int v = 0; v < s.domain.vertex_count; ++v) {
      const double exact = std::log(p[v].norm() / a) / std::log(b / a);
      worst = std::max(worst, std::abs(m.scalar_map("profile")[v] - exact));
    }
    h.push_back(2.0 * std::numbers::pi * b / segments);
    error.push_back(worst);
  }
  // Least-squares slope of log(error) against log(h).
  double mx = 0.0, my = 0.0;
  for (size_t i = 0; i < h.size(); ++i) mx += std::log(h[i]) / 3.0, my += std::log(error[i]) / 3.0;
  double sxy = 0.0, sxx = 0.0;
  for (size_t i = 0; i < h.size(); ++i)
    sxy += (std::log(h[i]) - mx) * (std::log(error[i]) - my), sxx += (std::log(h[i]) - mx) * (std::log(h[i]) - mx);
  const double order = sxy / sxx;
  EXPECT_NEAR(order, 2.0, 0.25) << "errors " << error[0] << ", " << error[1] << ", " << error[2];
  EXPECT_LT(error.back(), 1e-3);
}

// Several regions with several values: the result equals each value on its region and stays within
// the smallest and largest value elsewhere (the discrete maximum principle of a Delaunay mesh).
TEST(MapToolsLaplace, HoldsEachRegionAtItsValueAndStaysBetweenThem) {
  const PreparedSurface s = surface_from(testing::make_icosphere(3));
  const EvaluatedMaps m = evaluate_json(
      {{"north", {{"half_space", {{"point", {0.0, 0.0, 0.8}}, {"normal", {0.0, 0.0, 1.0}}}}}},
       {"south", {{"half_space", {{"point", {0.0, 0.0, -0.8}}, {"normal", {0.0, 0.0, -1.0}}}}}},
       {"east", {{"sphere", {{"center", {1.0, 0.0, 0.0}}, {"radius", 0.3}}}}},
       {"field", {{"laplace", json::array({{{"region", "north"}, {"value", 2.0}},
                                           {{"region", "south"}, {"value", -1.0}},
                                           {{"region", "east"}, {"value", 0.5}}})}}}},
      s);
  const std::vector<Eigen::Vector3d> p = intrinsic_vertex_positions(s);
  int held = 0;
  for (int v = 0; v < s.domain.vertex_count; ++v) {
    const double u = m.scalar_map("field")[v];
    const bool north = p[v].z() >= 0.8, south = p[v].z() <= -0.8, east = (p[v] - Eigen::Vector3d(1.0, 0.0, 0.0)).norm() <= 0.3;
    if (north) {
      EXPECT_EQ(u, 2.0);
    }
    if (south) {
      EXPECT_EQ(u, -1.0);
    }
    if (east) {
      EXPECT_EQ(u, 0.5);
    }
    if (north || south || east) {
      ++held;
    } else {
      EXPECT_GT(u, -1.0);
      EXPECT_LT(u, 2.0);
    }
  }
  EXPECT_GT(held, 0);
}

TEST(MapToolsLaplace, BadSetupsAreRefusedNamingTheMapAndTheRegion) {
  const PreparedSurface s = surface_from(testing::make_flat_rectangle(0.0, 1.0, 0.0, 1.0, 8, 8));
  const json left = {{"box", {{"min", {-1.0, -1.0, -1.0}}, {"max", {0.01, 2.0, 1.0}}}}};
  const json nowhere = {{"sphere", {{"center", {5.0, 5.0, 5.0}}, {"radius", 0.1}}}};
  const json wide = {{"box", {{"min", {-1.0, -1.0, -1.0}}, {"max", {0.5, 2.0, 1.0}}}}};
  auto error_of = [&](const json& maps) { return testing::input_error_of([&] { evaluate_json(maps, s); }); };
  auto laplace = [](std::initializer_list<std::pair<const char*, double>> regions) {
    json list = json::array();
    for (const auto& [name, value] : regions) list.push_back({{"region", name}, {"value", value}});
    return json{{"laplace", list}};
  };

  std::string e = error_of({{"left", left}, {"nowhere", nowhere}, {"f", laplace({{"left", 0.0}, {"nowhere", 1.0}})}});
  EXPECT_NE(e.find("map 'f'"), std::string::npos) << e;
  EXPECT_NE(e.find("region 'nowhere' holds no vertex"), std::string::npos) << e;

  e = error_of({{"left", left}, {"wide", wide}, {"f", laplace({{"left", 0.0}, {"wide", 1.0}})}});
  EXPECT_NE(e.find("regions 'left' (value 0.000000) and 'wide' (value 1.000000) overlap at intrinsic vertex"), std::string::npos) << e;
  // Overlapping with the same value is fine.
  EXPECT_EQ(error_of({{"left", left}, {"wide", wide}, {"f", laplace({{"left", 1.0}, {"wide", 1.0}})}}), "");

  e = error_of({{"f", {{"laplace", json::array()}}}});
  EXPECT_NE(e.find("map 'f': \"laplace\" = [] must be a non-empty list of regions"), std::string::npos) << e;
  e = error_of({{"f", {{"laplace", json::array({{{"region", "left"}}})}}}, {"left", left}});
  EXPECT_NE(e.find("missing \"value\""), std::string::npos) << e;
  e = error_of({{"f", {{"laplace", json::array({{{"region", 3}, {"value", 1.0}}})}}}});
  EXPECT_NE(e.find("\"laplace\"[0]: \"region\" must be a scalar map, by name or inline"), std::string::npos) << e;
  e = error_of({{"f", {{"laplace", json::array({{{"region", "left"}, {"value", 1.0}, {"weight", 2}}})}}}, {"left", left}});
  EXPECT_NE(e.find("unknown field \"weight\""), std::string::npos) << e;
  e = error_of({{"f", laplace({{"ghost", 1.0}})}});
  EXPECT_NE(e.find("reads map 'ghost', which is not defined"), std::string::npos) << e;
  // A region must be a scalar map.
  e = error_of({{"east", {{"direction", {1.0, 0.0, 0.0}}}}, {"f", laplace({{"east", 1.0}})}});
  EXPECT_NE(e.find("reads map 'east', a vector map, where a scalar map is needed"), std::string::npos) << e;
}

// A component that touches no region has no determined value: refused, naming where it is.
TEST(MapToolsLaplace, AComponentWithoutARegionIsRefused) {
  InputMesh two = testing::make_flat_rectangle(0.0, 1.0, 0.0, 1.0, 4, 4);
  const InputMesh other = testing::make_flat_rectangle(3.0, 4.0, 0.0, 1.0, 4, 4);
  const int offset = two.vertex_count();
  for (const Eigen::Vector3d& p : other.positions) two.positions.push_back(p), two.file_vertex.push_back(two.vertex_count() - 1);
  for (const auto& t : other.triangles) two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const PreparedSurface s = surface_from(two);
  const std::string e = testing::input_error_of([&] {
    evaluate_json({{"left", {{"box", {{"min", {-1.0, -1.0, -1.0}}, {"max", {0.01, 2.0, 1.0}}}}}},
                   {"f", {{"laplace", json::array({{{"region", "left"}, {"value", 1.0}}})}}}},
                  s);
  });
  EXPECT_NE(e.find("map 'f': the surface has 2 connected components, and the one with intrinsic vertex 25 (25 vertices) "
                   "touches no region"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace physarum
