// A sketch's regions (common/sketch/sketch_regions.hpp) against what the test draws: clusters of
// spots on lattices of known spacing, one per quadrant, give each quadrant its own area and spacing
// (the Delaunay edges between clusters are left out), an empty quadrant takes its nearest
// neighbour's attributes, and the blend between regions is bilinear between their centres.
#include "common/base/errors.hpp"
#include "common/sketch/sketch_regions.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace physarum {
namespace {

// A 3 x 3 square lattice of circles of radius r and spacing s around c.
void cluster(Sketch& sketch, Eigen::Vector2d c, double r, double s) {
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) sketch.spots.push_back({c + Eigen::Vector2d(i * s, j * s), r, r, 0.0});
}

TEST(SketchRegions, EachQuadrantHasItsOwnSizeAndSpacing) {
  Sketch sketch;
  sketch.source = "test";
  cluster(sketch, {0.25, 0.25}, 0.01, 0.05);
  cluster(sketch, {0.75, 0.25}, 0.02, 0.08);
  cluster(sketch, {0.25, 0.75}, 0.03, 0.12);
  const SketchRegions regions = sketch_regions(sketch, measure_sketch(sketch), 2);
  ASSERT_EQ(regions.regions.size(), 4u);
  const double radius[] = {0.01, 0.02, 0.03}, spacing[] = {0.05, 0.08, 0.12};
  for (int k = 0; k < 3; ++k) {
    const RegionAttributes& r = regions.regions[static_cast<size_t>(k)];
    EXPECT_EQ(r.spots, 9) << k;
    EXPECT_NEAR(r.area, M_PI * radius[k] * radius[k], 1e-12) << k;
    // A square lattice's Delaunay edges: 12 sides s and 4 diagonals s sqrt(2); the median is s.
    EXPECT_NEAR(r.spacing, spacing[k], 1e-12) << k;
  }
  // The empty top-right quadrant: its nearest neighbours (by centre) are at equal distance; the
  // first of them, bottom-right (index 1), lends it its attributes.
  EXPECT_EQ(regions.regions[3].spots, 0);
  EXPECT_EQ(regions.regions[3].filled_from, 1);
  EXPECT_EQ(regions.regions[3].area, regions.regions[1].area);
}

TEST(SketchRegions, TheBlendIsBilinearBetweenRegionCentres) {
  SketchRegions regions;
  regions.n = 2;
  regions.window = {2.0, 1.0};
  const std::vector<double> value = {1.0, 2.0, 3.0, 5.0};  // bottom-left, bottom-right, top-left, top-right
  EXPECT_DOUBLE_EQ(regions.blend(value, {0.5, 0.25}), 1.0);   // a centre is its region's value
  EXPECT_DOUBLE_EQ(regions.blend(value, {1.5, 0.75}), 5.0);
  EXPECT_DOUBLE_EQ(regions.blend(value, {1.0, 0.5}), 2.75);   // the middle: the mean of the four
  EXPECT_DOUBLE_EQ(regions.blend(value, {1.0, 0.25}), 1.5);   // halfway along the bottom row
  EXPECT_DOUBLE_EQ(regions.blend(value, {0.0, 0.0}), 1.0);    // constant beyond the outer centres
  EXPECT_EQ(regions.region_of({1.9, 0.1}), 1);
  EXPECT_EQ(regions.region_of({0.1, 0.9}), 2);
  EXPECT_EQ(regions.region_of({2.0, 1.0}), 3);  // the window's far corner belongs to the last region
}

// Strokes: a region's orientation is the length-weighted axial mean of the segments whose midpoints
// lie in it (a polyline crossing regions counts in each), its width the length-weighted class width.
TEST(SketchRegions, StrokesGiveEachRegionTheirOrientationAndWidth) {
  Sketch sketch;
  sketch.source = "test";
  sketch.window = {2.0, 1.0};
  // Bottom-left: two strokes at 10 and 170 degrees (axes 20 degrees apart across 0): mean 0, not 90.
  const double a = 10.0 * M_PI / 180.0;
  sketch.strokes.push_back({{{0.3, 0.2}, {0.3 + 0.4 * std::cos(a), 0.2 + 0.4 * std::sin(a)}}, 1});
  sketch.strokes.push_back({{{0.7, 0.3}, {0.7 - 0.4 * std::cos(a), 0.3 + 0.4 * std::sin(a)}}, 1});
  // One polyline from bottom-right (a segment 3 long at 45 degrees, class 4) into top-right (one 1 long at 90).
  sketch.strokes.push_back({{{1.1, 0.1}, {1.1 + 0.3 / std::sqrt(2.0), 0.1 + 0.3 / std::sqrt(2.0)}, {1.1 + 0.3 / std::sqrt(2.0), 0.9}}, 4});
  // Top-left: a long class-1 stroke at 30 degrees and a short class-3 one at 120: the weights 3 : 1.
  const double b = 30.0 * M_PI / 180.0, c = 120.0 * M_PI / 180.0;
  sketch.strokes.push_back({{{0.2, 0.6}, {0.2 + 0.3 * std::cos(b), 0.6 + 0.3 * std::sin(b)}}, 1});
  sketch.strokes.push_back({{{0.6, 0.7}, {0.6 + 0.1 * std::cos(c), 0.7 + 0.1 * std::sin(c)}}, 3});
  const SketchRegions regions = stroke_regions(sketch, 2);
  ASSERT_EQ(regions.regions.size(), 4u);
  const double unit = kStripeWidthPerClass * 2.0;  // a class's width: a fraction of the window's width (2)
  EXPECT_EQ(regions.regions[0].strokes, 2);
  EXPECT_NEAR(regions.regions[0].orientation, 0.0, 1e-9);
  EXPECT_NEAR(regions.regions[0].width, unit, 1e-12);
  EXPECT_EQ(regions.regions[1].strokes, 1);
  EXPECT_NEAR(regions.regions[1].orientation, 45.0, 1e-9);
  EXPECT_NEAR(regions.regions[1].width, 4 * unit, 1e-12);
  EXPECT_NEAR(regions.regions[3].orientation, 90.0, 1e-9);
  // Doubled angles 60 and 240 weighted 3 and 1: 3 e^{i 60} + e^{i 240} = 2 e^{i 60}: the axis at 30.
  EXPECT_NEAR(regions.regions[2].orientation, 30.0, 1e-9);
  EXPECT_NEAR(regions.regions[2].width, (0.3 * 1 + 0.1 * 3) / 0.4 * unit, 1e-12);
  EXPECT_THROW(stroke_regions(Sketch{}, 2), InputError);
}

TEST(SketchRegions, ASketchWithoutSpotsIsRefused) {
  Sketch sketch;
  sketch.source = "strokes.json";
  sketch.strokes.push_back({{{0.1, 0.1}, {0.9, 0.9}}, 2, 0.0});
  try {
    sketch_regions(sketch, measure_sketch(sketch), 2);
    ADD_FAILURE() << "a sketch of strokes only gave regions of spots";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("strokes.json: the sketch has no spot"), std::string::npos) << e.what();
  }
}

// Two regions side by side, on two charts: between their centres the plain blend is linear; a
// point on the left chart takes the left region's value alone (the right one's weight dropped and
// the rest renormalised), one with no chart the plain blend.
TEST(SketchRegions, ABlendKeepsToThePointsChart) {
  SketchRegions regions;
  regions.n = 2;
  regions.window = {1.0, 1.0};
  regions.regions.resize(4);
  regions.chart = {0, 1, 0, 1};
  const std::vector<double> value = {1.0, 3.0, 1.0, 3.0};
  EXPECT_DOUBLE_EQ(regions.blend(value, {0.5, 0.5}), 2.0);
  EXPECT_DOUBLE_EQ(regions.blend(value, {0.4, 0.5}), 1.0 + 2.0 * 0.3);
  EXPECT_DOUBLE_EQ(regions.blend(value, {0.4, 0.5}, 0), 1.0);
  EXPECT_DOUBLE_EQ(regions.blend(value, {0.6, 0.3}, 1), 3.0);
  EXPECT_DOUBLE_EQ(regions.blend(value, {0.4, 0.5}, -1), 1.6);
}

}  // namespace
}  // namespace physarum
