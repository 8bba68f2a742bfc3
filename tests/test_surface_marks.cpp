// Marks drawn on a surface (common/sketch/surface_marks.hpp), against answers known on a flat square
// and a sphere: a mark above the surface lands on it, its direction in the tangent plane; the
// geodesic spacing of marks on the flat unit square is their straight distance (fast marching from
// the marks themselves, inserted as vertices, is exact there up to rounding of the 1 % of an edge they
// may move); on the unit sphere, marks at the poles are pi apart (the icosphere's polyhedral
// distance, within 1 %); the weights make a mark's own value hold at its point; bad marks are refused.
#include "common/base/errors.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/sketch/sketch.hpp"
#include "common/sketch/surface_marks.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;

json mark(Eigen::Vector3d p, double a, double b, Eigen::Vector3d d) {
  return {{"ellipse", {{"surface_point", {p.x(), p.y(), p.z()}}, {"radii", {a, b}}, {"direction", {d.x(), d.y(), d.z()}}}}};
}

TEST(SurfaceMarks, MarksLandOnTheSquareWithTheirGeodesicSpacing) {
  const InputMesh square = load_mesh("shape:square");
  const Sketch sketch = sketch_from_json({{"marks",
                                           {mark({0.2, 0.3, 0.1}, 0.04, 0.02, {1, 0, 1}),    // above the square, tilted
                                            mark({0.7, 0.3, 0.0}, 0.03, 0.03, {0, 1, 0}),
                                            mark({0.2, 0.8, 0.0}, 0.02, 0.04, {1, 0, 0})}}},  // major axis across x
                                         "marks.json");
  const SurfaceMarks marks = place_surface_marks(sketch, square);
  ASSERT_EQ(marks.size(), 3u);
  EXPECT_TRUE(marks.point[0].isApprox(Eigen::Vector3d(0.2, 0.3, 0.0), 1e-12)) << marks.point[0].transpose();
  EXPECT_NEAR(std::abs(marks.axis[0].x()), 1.0, 1e-12) << "(1, 0, 1) projected into z = 0";
  EXPECT_NEAR(std::abs(marks.axis[2].y()), 1.0, 1e-12) << "the first radius is the minor one";
  EXPECT_NEAR(marks.area[0], M_PI * 0.04 * 0.02, 1e-15);
  EXPECT_NEAR(marks.aspect[0], 0.5, 1e-15);
  // Each mark's nearest other: 0 -> 1 and 1 -> 0 at 0.5, 2 -> 0 at 0.5.
  for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(marks.spacing[k], 0.5, 1e-3 * 0.5) << k;
  // At a mark, its own weight is (all but) 1; everywhere the weights sum to 1.
  for (size_t k = 0; k < 3; ++k) EXPECT_GT(marks.weights(marks.point[k])[k], 0.999) << k;
  for (size_t v = 0; v < square.positions.size(); v += 37) {
    const std::vector<double> w = marks.weights(v);
    EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-12);
  }
  EXPECT_EQ(marks.nearest({0.6, 0.35, 0.0}), 1);
  EXPECT_LT(marks.ellipse_radius(0, {0.2 + 0.039, 0.3, 0.0}), 1.0) << "inside along the major axis";
  EXPECT_GT(marks.ellipse_radius(0, {0.2, 0.3 + 0.021, 0.0}), 1.0) << "outside across it";
}

TEST(SurfaceMarks, MarksAtThePolesOfASphereArePiApart) {
  const InputMesh sphere = load_mesh("shape:sphere");
  const Sketch sketch = sketch_from_json(
      {{"marks", {mark({0, 0, 1.2}, 0.05, 0.05, {1, 0, 0}), mark({0, 0, -1.1}, 0.05, 0.05, {0, 1, 0})}}}, "poles.json");
  const SurfaceMarks marks = place_surface_marks(sketch, sphere);
  EXPECT_NEAR(marks.point[0].norm(), 1.0, 1e-9) << "the pole is a vertex of the icosphere";
  for (size_t k = 0; k < 2; ++k) EXPECT_NEAR(marks.spacing[k], M_PI, 0.01 * M_PI) << k;
}

TEST(SurfaceMarks, BadMarksAreRefusedNamingTheMark) {
  const InputMesh square = load_mesh("shape:square");
  auto refusal = [&](const json& m) {
    try {
      place_surface_marks(sketch_from_json({{"marks", {m}}}, "bad.json"), square);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal(mark({0.5, 0.5, 0.0}, 0.03, 0.02, {0, 0, 1})).find("bad.json: mark 0: its direction is (nearly) normal to the surface"),
            std::string::npos);
  EXPECT_NE(refusal(mark({0.5, 0.5, 3.0}, 0.03, 0.02, {1, 0, 0})).find("bad.json: mark 0: its surface_point lies 3 from"),
            std::string::npos);
}

}  // namespace
}  // namespace physarum
