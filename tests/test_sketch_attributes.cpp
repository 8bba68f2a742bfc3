// A sketch's attributes against the marks the test draws itself (common/sketch/): ellipses given as
// JSON are measured exactly (area pi a b, aspect, orientation as an axis in [0, 180)); spots on a
// hexagonal lattice of spacing s have Delaunay neighbours at s; a picture drawn by the test gives its
// filled and outlined ellipses back within 3 % in area and 3 degrees in orientation and their
// spacing within 5 %, a thick line as a stroke along its direction, a red mark as a stroke; and
// each bad sketch is refused with its reason.
#include "common/base/errors.hpp"
#include "common/sketch/sketch_attributes.hpp"
#include "common/sketch/sketch_image.hpp"
#include "test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

double angle_difference(double a, double b) {
  const double d = std::fmod(std::fabs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

TEST(SketchJson, EllipsesAreMeasuredExactlyAndTheirAxesNormalized) {
  const Sketch sketch = sketch_from_json(
      {{"window", {2.0, 1.0}},
       {"marks",
        {{{"ellipse", {{"center", {0.2, 0.3}}, {"radii", {0.04, 0.02}}, {"angle", 30.0}}}},
         {{"ellipse", {{"center", {1.2, 0.3}}, {"radii", {0.02, 0.04}}, {"angle", 30.0}}}},
         {{"ellipse", {{"center", {1.5, 0.6}}, {"radii", {0.05, 0.01}}, {"angle", 210.0}}}},
         {{"stroke", {{"points", {{0.1, 0.8}, {0.6, 0.8}, {0.6, 0.9}}}, {"width", 3}}}}}}},
      "sketch.json");
  const SketchAttributes a = measure_sketch(sketch);
  ASSERT_EQ(a.spots.size(), 3u);
  EXPECT_NEAR(a.spots[0].area, M_PI * 0.04 * 0.02, 1e-15);
  EXPECT_DOUBLE_EQ(a.spots[0].aspect, 0.5);
  EXPECT_NEAR(a.spots[0].orientation, 30.0, 1e-12);
  EXPECT_NEAR(a.spots[1].orientation, 120.0, 1e-12) << "the major radius is the second: across the angle";
  EXPECT_NEAR(a.spots[2].orientation, 30.0, 1e-12) << "an ellipse turned by 180 degrees is the same";
  ASSERT_EQ(a.strokes.size(), 1u);
  // Segments of length 0.5 at 0 degrees and 0.1 at 90: doubled angles (1, 0) * 0.5 + (-1, 0) * 0.1.
  EXPECT_NEAR(a.strokes[0].orientation, 0.0, 1e-12);
  EXPECT_NEAR(a.strokes[0].length, 0.6, 1e-12);
  EXPECT_EQ(a.strokes[0].width_class, 3);
}

TEST(SketchJson, SurfaceMarksKeepTheirPointRadiiAndDirection) {
  // The first radius is the minor one: the major axis lies across the direction.
  const Sketch s = sketch_from_json(
      {{"marks", {{{"ellipse", {{"surface_point", {0.1, 0.2, 0.3}}, {"radii", {0.02, 0.05}}, {"direction", {0, 2, 0}}}}}}}}, "s.json");
  ASSERT_EQ(s.surface_spots.size(), 1u);
  EXPECT_TRUE(s.spots.empty());
  EXPECT_TRUE(s.surface_spots[0].point.isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  EXPECT_DOUBLE_EQ(s.surface_spots[0].major, 0.05);
  EXPECT_DOUBLE_EQ(s.surface_spots[0].minor, 0.02);
  EXPECT_TRUE(s.surface_spots[0].direction.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(s.surface_spots[0].across);
}

TEST(SketchJson, BadSketchesAreRefusedWithTheirReason) {
  auto bad = [](const json& j) { return refusal([&] { sketch_from_json(j, "s.json"); }); };
  EXPECT_NE(bad({{"marks", json::array()}}).find("s.json: the sketch has no \"marks\""), std::string::npos);
  EXPECT_NE(bad({{"marks", {{{"ellipse", {{"center", {0.5, 0.5}}, {"radii", {0.1, 0.0}}}}}}}}).find("mark 0: \"radii\" must both be > 0"),
            std::string::npos);
  EXPECT_NE(bad({{"marks", {{{"ellipse", {{"center", {1.5, 0.5}}, {"radii", {0.1, 0.1}}}}}}}}).find("outside the window"),
            std::string::npos);
  EXPECT_NE(bad({{"marks", {{{"stroke", {{"points", {{0.1, 0.1}, {0.2, 0.2}}}, {"width", 5}}}}}}}).find("width class 1..4"),
            std::string::npos);
  EXPECT_NE(bad({{"marks", {{{"ellipse", {{"surface_point", {0, 0, 1}}, {"radii", {0.1, 0.1}}}}}}}}).find("mark 0: missing \"direction\""),
            std::string::npos);
  EXPECT_NE(bad({{"marks", {{{"ellipse", {{"surface_point", {0, 0, 1}}, {"radii", {0.1, 0.1}}, {"direction", {0, 0, 0}}}}}}}})
                .find("mark 0: \"direction\" must not be zero"),
            std::string::npos);
  EXPECT_NE(bad({{"marks",
                  {{{"ellipse", {{"surface_point", {0, 0, 1}}, {"radii", {0.1, 0.1}}, {"direction", {1, 0, 0}}}}},
                   {{"ellipse", {{"center", {0.5, 0.5}}, {"radii", {0.1, 0.1}}}}}}}})
                .find("mixes marks on the surface"),
            std::string::npos);
  EXPECT_NE(bad({{"marks", {{{"blob", json::object()}}}}}).find("unknown kind \"blob\""), std::string::npos);
}

// A hexagonal lattice: every interior site has six Delaunay neighbours at exactly the lattice
// spacing (no four sites are cocircular, so the triangulation is unique).
std::vector<Eigen::Vector2d> hexagonal_lattice(double s, int columns, int rows, Eigen::Vector2d origin) {
  std::vector<Eigen::Vector2d> points;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) points.push_back(origin + Eigen::Vector2d((i + 0.5 * (j % 2)) * s, j * s * std::sqrt(3.0) / 2));
  return points;
}

bool interior(int index, int columns, int rows) {
  const int i = index % columns, j = index / columns;
  return i > 0 && j > 0 && i < columns - 1 && j < rows - 1;
}

TEST(SketchSpacing, InteriorSpotsOfAHexagonalLatticeHaveSixNeighboursAtTheSpacing) {
  const std::vector<Eigen::Vector2d> centres = hexagonal_lattice(0.1, 7, 7, {0.1, 0.1});
  json marks = json::array();
  for (const Eigen::Vector2d& c : centres) marks.push_back({{"ellipse", {{"center", {c.x(), c.y()}}, {"radii", {0.02, 0.02}}}}});
  const SketchAttributes a = measure_sketch(sketch_from_json({{"marks", marks}}, "lattice.json"));
  for (size_t k = 0; k < a.spots.size(); ++k) {
    if (!interior(static_cast<int>(k), 7, 7)) continue;
    EXPECT_EQ(a.spots[k].neighbours.size(), 6u) << "spot " << k;
    EXPECT_NEAR(a.spots[k].spacing, 0.1, 1e-7) << "spot " << k;
  }
  EXPECT_TRUE(delaunay_neighbours({{0.5, 0.5}}).at(0).empty());
  EXPECT_EQ(delaunay_neighbours({{0.1, 0.1}, {0.5, 0.5}}).at(0), std::vector<int>{1});
}

// ---- pictures drawn by the test ----

constexpr int kSide = 800;  // pixels; the window is [0, 1]^2, a pixel 1/800

struct Canvas {
  std::vector<float> rgb = std::vector<float>(static_cast<size_t>(kSide) * kSide * 3, 1.0f);
  // Paints every pixel whose centre (in window coordinates, y up) `inside` accepts.
  void paint(const std::function<bool(const Eigen::Vector2d&)>& inside, std::array<float, 3> colour = {0.1f, 0.1f, 0.1f}) {
    for (int row = 0; row < kSide; ++row)
      for (int col = 0; col < kSide; ++col) {
        const Eigen::Vector2d p((col + 0.5) / kSide, (kSide - row - 0.5) / kSide);
        if (!inside(p)) continue;
        for (int c = 0; c < 3; ++c) rgb[(static_cast<size_t>(row) * kSide + static_cast<size_t>(col)) * 3 + static_cast<size_t>(c)] = colour[static_cast<size_t>(c)];
      }
  }
  void write(const fs::path& path) const {
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(kSide, kSide, 3, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
    out->close();
  }
};

// The ellipse's implicit value at p: < 1 inside.
double ellipse_value(const Eigen::Vector2d& p, const Eigen::Vector2d& c, double a, double b, double degrees) {
  const double t = degrees * M_PI / 180.0;
  const Eigen::Vector2d d = p - c;
  const double u = d.x() * std::cos(t) + d.y() * std::sin(t), v = -d.x() * std::sin(t) + d.y() * std::cos(t);
  return (u * u) / (a * a) + (v * v) / (b * b);
}

TEST(SketchImage, DrawnEllipsesComeBackWithinTheStatedTolerances) {
  TempDir dir;
  Canvas canvas;
  // A 5 x 5 hexagonal lattice (spacing 0.15) of ellipses 0.04 x 0.02 at angles that vary over it.
  const std::vector<Eigen::Vector2d> centres = hexagonal_lattice(0.15, 5, 5, {0.17, 0.17});
  std::vector<double> angles;
  for (size_t k = 0; k < centres.size(); ++k) {
    angles.push_back(7.0 * static_cast<double>(k));
    canvas.paint([&](const Eigen::Vector2d& p) { return ellipse_value(p, centres[k], 0.04, 0.02, angles.back()) < 1.0; });
  }
  canvas.write(dir.path / "spots.png");
  const Sketch sketch = sketch_from_image((dir.path / "spots.png").string());
  EXPECT_DOUBLE_EQ(sketch.window.y(), 1.0);
  EXPECT_TRUE(sketch.strokes.empty());
  const SketchAttributes a = measure_sketch(sketch);
  ASSERT_EQ(a.spots.size(), centres.size());
  for (const SpotAttributes& s : a.spots) {
    size_t k = 0;
    for (size_t m = 1; m < centres.size(); ++m)
      if ((centres[m] - s.center).norm() < (centres[k] - s.center).norm()) k = m;
    EXPECT_LT((centres[k] - s.center).norm(), 1.0 / kSide) << "spot " << k;
    EXPECT_NEAR(s.area, M_PI * 0.04 * 0.02, 0.03 * M_PI * 0.04 * 0.02) << "spot " << k;
    EXPECT_LT(angle_difference(s.orientation, angles[k]), 3.0) << "spot " << k << ": " << s.orientation;
    EXPECT_NEAR(s.aspect, 0.5, 0.05) << "spot " << k;
    if (interior(static_cast<int>(k), 5, 5)) {
      EXPECT_NEAR(s.spacing, 0.15, 0.05 * 0.15) << "spot " << k;
    }
  }
}

TEST(SketchImage, AnOutlinedEllipseIsASpotMeasuredToItsLinesMiddleAndLinesAreStrokes) {
  TempDir dir;
  Canvas canvas;
  // An outline 5 pixels wide along the ellipse 0.12 x 0.06 at 40 degrees centred (0.3, 0.7).
  const double half = 2.5 / kSide;
  canvas.paint([&](const Eigen::Vector2d& p) {
    return ellipse_value(p, {0.3, 0.7}, 0.12 + half, 0.06 + half, 40.0) < 1.0 &&
           ellipse_value(p, {0.3, 0.7}, 0.12 - half, 0.06 - half, 40.0) >= 1.0;
  });
  // A line 0.4 long and 0.012 wide at 150 degrees through (0.6, 0.3).
  canvas.paint([&](const Eigen::Vector2d& p) { return ellipse_value(p, {0.6, 0.3}, 0.2, 0.006, 150.0) < 1.0 &&
                                                      std::fabs(ellipse_value(p, {0.6, 0.3}, 0.2, 1e9, 150.0)) < 1.0; });
  // A red disc: a stroke by its colour.
  canvas.paint([&](const Eigen::Vector2d& p) { return (p - Eigen::Vector2d(0.8, 0.8)).norm() < 0.05; }, {0.9f, 0.1f, 0.1f});
  canvas.write(dir.path / "mixed.png");
  const SketchAttributes a = measure_sketch(sketch_from_image((dir.path / "mixed.png").string()));
  ASSERT_EQ(a.spots.size(), 1u);
  EXPECT_NEAR(a.spots[0].area, M_PI * 0.12 * 0.06, 0.03 * M_PI * 0.12 * 0.06);
  EXPECT_LT(angle_difference(a.spots[0].orientation, 40.0), 3.0) << a.spots[0].orientation;
  ASSERT_EQ(a.strokes.size(), 2u);
  const StrokeAttributes& line = a.strokes[0].length > 0.3 ? a.strokes[0] : a.strokes[1];
  EXPECT_LT(angle_difference(line.orientation, 150.0), 3.0) << line.orientation;
  EXPECT_NEAR(line.length, 0.4, 0.02);
  EXPECT_NEAR(line.width, 0.012 * M_PI / 4, 0.003) << "a thin ellipse's area over its length";
  EXPECT_EQ(line.width_class, 1);
}

TEST(SketchImage, BadPicturesAreRefusedWithTheirReason) {
  TempDir dir;
  Canvas blank;
  blank.write(dir.path / "blank.png");
  EXPECT_NE(refusal([&] { sketch_from_image((dir.path / "blank.png").string()); }).find("no marks"), std::string::npos);
  Canvas speck;
  speck.paint([](const Eigen::Vector2d& p) { return (p - Eigen::Vector2d(0.5, 0.5)).norm() < 0.5 / kSide * 3; });
  speck.write(dir.path / "speck.png");
  const std::string small = refusal([&] { sketch_from_image((dir.path / "speck.png").string()); });
  EXPECT_NE(small.find("a mark needs 20 or more"), std::string::npos) << small;
  std::ofstream(dir.path / "text.png") << "not an image";
  EXPECT_NE(refusal([&] { sketch_from_image((dir.path / "text.png").string()); }).find("cannot read the sketch image"),
            std::string::npos);
}

}  // namespace
}  // namespace physarum::testing
