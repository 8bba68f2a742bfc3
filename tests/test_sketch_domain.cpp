// Where a sketch window lies on a surface (common/sketch/sketch_domain.hpp), against maps known in
// closed form: the UV rectangle of uv_test_meshes.hpp maps 1.5 m of x onto 0.4 of u and 1 m of y onto
// 0.8 of v in each of its two charts, so a window unit is 3.75 m along x and 1.25 m along y there, a
// window circle an ellipse of aspect 1/3 along x; points between the charts lie on no face; a vertex
// on the seam has a window point per chart. The cube's 3 x 2 tiles are square in a 3 : 2 window.
#include "common/base/errors.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/sketch/sketch_domain.hpp"
#include "uv_test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace physarum {
namespace {

Sketch window(double w, double h) {
  Sketch s;
  s.window = {w, h};
  s.source = "test sketch";
  return s;
}

TEST(SketchDomain, AUvLayoutsStretchIsEachFacesOwnMap) {
  const InputMesh mesh = testing::make_uv_rectangle();
  const SketchDomain domain = SketchDomain::uv(window(1.0, 1.0), mesh, 3.0);  // the rectangle's own area: 1 m per unit
  ASSERT_TRUE(domain.on_uv());
  EXPECT_NEAR(domain.scale(), 1.0, 1e-12);
  for (const Eigen::Vector2d& w : {Eigen::Vector2d(0.25, 0.5), Eigen::Vector2d(0.7, 0.2)}) {
    const WindowFrame at = domain.frame_at(w);
    EXPECT_NEAR(at.area_factor(), 3.75 * 1.25, 1e-9);
    EXPECT_TRUE(at.to_surface({1.0, 0.0}).isApprox(Eigen::Vector3d(3.75, 0.0, 0.0), 1e-9)) << at.to_surface({1.0, 0.0}).transpose();
    EXPECT_TRUE(at.to_surface({0.0, 1.0}).isApprox(Eigen::Vector3d(0.0, 1.25, 0.0), 1e-9)) << at.to_surface({0.0, 1.0}).transpose();
    const EllipseShape circle = on_surface(at, {1.0, 0.0});
    EXPECT_NEAR(circle.aspect, 1.0 / 3.0, 1e-9);
    EXPECT_NEAR(std::min(circle.orientation, 180.0 - circle.orientation), 0.0, 1e-6);
    // A window ellipse twice as tall as wide is 3.75 / 2.5 = 1.5 times as wide as tall on the surface.
    const EllipseShape tall = on_surface(at, {0.5, 90.0});
    EXPECT_NEAR(tall.aspect, 1.0 / 1.5, 1e-9);
    EXPECT_NEAR(std::min(tall.orientation, 180.0 - tall.orientation), 0.0, 1e-6);
    // Pulled back, any ellipse is the one drawn.
    const EllipseShape back = in_window(at, on_surface(at, {0.4, 70.0}));
    EXPECT_NEAR(back.aspect, 0.4, 1e-9);
    EXPECT_NEAR(back.orientation, 70.0, 1e-6);
  }
  // x = 2 lies in the right chart: u = 0.55 + 0.4 (0.5 / 1.5).
  const SketchDomain::Located at = domain.locate({2.0, 0.5, 0.0});
  EXPECT_TRUE(at.window_point.isApprox(Eigen::Vector2d(0.55 + 0.4 / 3.0, 0.5), 1e-9)) << at.window_point.transpose();
  const std::optional<Eigen::Vector3d> back = domain.surface_point(at.window_point);
  ASSERT_TRUE(back.has_value());
  EXPECT_TRUE(back->isApprox(Eigen::Vector3d(2.0, 0.5, 0.0), 1e-9)) << back->transpose();
  EXPECT_FALSE(domain.surface_point({0.5, 0.5}).has_value()) << "u = 0.5 lies between the charts";
  EXPECT_FALSE(domain.surface_point({0.3, 0.95}).has_value()) << "v = 0.95 lies above them";
  // The seam column's vertices (x = 1.5) have a window point in each chart.
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const std::vector<Eigen::Vector2d> points = domain.vertex_window_points(v);
    if (std::abs(mesh.positions[v].x() - 1.5) > 1e-12) {
      EXPECT_EQ(points.size(), 1u) << v;
      continue;
    }
    ASSERT_EQ(points.size(), 2u) << v;
    EXPECT_NEAR(std::abs(points[0].x() - points[1].x()), 0.1, 1e-9) << "u = 0.45 and 0.55";
  }
}

TEST(SketchDomain, TheLayoutsChartsAreItsPiecesJoinedByUvEdges) {
  const InputMesh mesh = testing::make_uv_rectangle();
  const SketchDomain domain = SketchDomain::uv(window(1.0, 1.0), mesh, 3.0);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const double x = (mesh.positions[mesh.triangles[f][0]] + mesh.positions[mesh.triangles[f][1]] + mesh.positions[mesh.triangles[f][2]]).x() / 3;
    EXPECT_EQ(domain.face_chart(f), x < 1.5 ? 0 : 1) << f;
  }
  EXPECT_EQ(domain.chart_at({0.25, 0.5}), 0);
  EXPECT_EQ(domain.chart_at({0.75, 0.5}), 1);
  EXPECT_EQ(domain.chart_at({0.5, 0.5}), -1) << "between the charts";
  const InputMesh cube = load_mesh("shape:cube");
  const SketchDomain tiles = SketchDomain::uv(window(1.5, 1.0), cube, 6.0);
  std::set<int> charts;
  for (size_t f = 0; f < cube.triangles.size(); ++f) charts.insert(tiles.face_chart(f));
  EXPECT_EQ(charts.size(), 6u) << "one chart per side";
}

TEST(SketchDomain, APatchIsTheWindowOnItsXyExtent) {
  const InputMesh square = load_mesh("shape:square");
  const SketchDomain domain = SketchDomain::patch(window(2.0, 1.0), square, 4.0);  // a 2 m square
  const WindowFrame at = domain.frame_at({0.3, 0.3});
  EXPECT_TRUE(at.stretch.isApprox(Eigen::Vector2d(1.0, 2.0).asDiagonal().toDenseMatrix(), 1e-12)) << at.stretch;
  EXPECT_TRUE(domain.locate({0.25, 0.5, 0.0}).window_point.isApprox(Eigen::Vector2d(0.5, 0.5), 1e-12));
  EXPECT_NEAR(domain.surface_area(), 4.0, 1e-12);
}

TEST(SketchDomain, TheCubesTilesAreSquareInAThreeByTwoWindow) {
  const InputMesh cube = load_mesh("shape:cube");
  const SketchDomain domain = SketchDomain::uv(window(1.5, 1.0), cube, 6.0);
  for (size_t f = 0; f < cube.triangles.size(); f += 101) {
    const EllipseShape circle = on_surface(domain.frame_of_face(f), {1.0, 0.0});
    EXPECT_NEAR(circle.aspect, 1.0, 1e-9) << f;
    EXPECT_NEAR(domain.frame_of_face(f).length_factor(), 2.0 / 0.92, 1e-9) << f;  // a tile: 0.92 / 2 of the window's height
  }
}

TEST(SketchDomain, AUvSketchOnAMeshWithoutUvsIsRefused) {
  try {
    SketchDomain::uv(window(1.0, 1.0), load_mesh("shape:sphere"), 1.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shape:sphere has no texture coordinates"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace physarum
