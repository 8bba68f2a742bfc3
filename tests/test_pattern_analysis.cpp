// Pattern analysis (issue 21): every measure against a known answer on synthetic fields —
// Gaussian disks (area pi r^2, converging as O(h^2)), rotated ellipses (aspect a/b, orientation theta),
// a hexagonal lattice (spacing s), parallel stripes, a stadium and a ring (width w), caps on the unit
// sphere (area 2 pi (1 - cos rho), spacing pi/2) — and `physarum analyze` on a run folder.
#include "common/base/errors.hpp"
#include "common/pattern/face_direction_field.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/pattern/pattern_analysis.hpp"
#include "common/output/pattern_histograms.hpp"
#include "common/pattern/pattern_segmentation.hpp"
#include "common/output/ply_writer.hpp"
#include "common/pattern/stripe_width.hpp"
#include "tests/test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>

namespace physarum {
namespace {

using testing::run_physarum;
using testing::TempDir;

// The unit square [0, 1]^2 in z = 0 cut into n x n cells, diagonals alternating like shape:square.
InputMesh square_grid(int n) {
  InputMesh mesh;
  mesh.source = "grid" + std::to_string(n);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) mesh.positions.emplace_back(double(i) / n, double(j) / n, 0.0);
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({a, c, d});
      } else {
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({b, c, d});
      }
    }
  return mesh;
}

InputVertexData<double> sample(const InputMesh& mesh, const std::function<double(const Eigen::Vector3d&)>& f) {
  InputVertexData<double> values(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) values[v] = f(mesh.positions[v]);
  return values;
}

// Gaussian bumps of width sigma at `centres`; the level exp(-r^2 / (2 sigma^2)) is the circle of radius r.
struct Bumps {
  std::vector<Eigen::Vector3d> centres;
  double sigma;
  double operator()(const Eigen::Vector3d& p) const {
    double f = 0.0;
    for (const Eigen::Vector3d& c : centres) f += std::exp(-(p - c).squaredNorm() / (2.0 * sigma * sigma));
    return f;
  }
  double level_of_radius(double r) const { return std::exp(-r * r / (2.0 * sigma * sigma)); }
};

PatternAnalysis analyse(const InputMesh& mesh, const InputVertexData<double>& field, double threshold) {
  PatternAnalysisOptions options;
  options.threshold = threshold;
  return analyze_pattern(mesh, field, options);
}

// ---- disks: count, area pi r^2 with an error that shrinks as h^2, aspect 1, centre ----
TEST(PatternAnalysis, DisksHaveAreaPiRSquaredConvergingWithRefinement) {
  const Bumps bumps{{{0.27, 0.31, 0}, {0.71, 0.26, 0}, {0.33, 0.74, 0}, {0.68, 0.69, 0}}, 0.06};
  const double r = 0.09, exact = M_PI * r * r;
  // The error oscillates with where the circle falls on the grid, under an envelope ~0.1 (h/r)^2.
  double coarse_error = 0.0, worst = 0.0;
  for (int n : {24, 48, 96, 192}) {
    const InputMesh mesh = square_grid(n);
    const PatternAnalysis a = analyse(mesh, sample(mesh, bumps), bumps.level_of_radius(r));
    ASSERT_EQ(a.regions.size(), 4u) << "n = " << n;
    worst = 0.0;
    for (size_t i = 0; i < 4; ++i) {
      const AnalysedRegion& spot = a.regions[i];
      EXPECT_FALSE(spot.is_stripe);
      EXPECT_EQ(spot.holes, 0);
      worst = std::max(worst, std::abs(spot.area - exact) / exact);
      // A near-circle: its aspect ratio is 1 + O((h/r)^2).
      const double h = 1.0 / n;
      EXPECT_NEAR(spot.shape.aspect_ratio, 1.0, (h / r) * (h / r)) << "n = " << n;
      double nearest = 1e9;
      for (const Eigen::Vector3d& c : bumps.centres) nearest = std::min(nearest, (spot.shape.centre - c).norm());
      EXPECT_LT(nearest, 0.05 * h) << "the centroid of a symmetric spot is its centre";
    }
    EXPECT_LT(worst, 0.2 * std::pow(1.0 / (n * r), 2)) << "n = " << n;  // O(h^2) with a stated constant
    if (n == 24) coarse_error = worst;
  }
  // h / 8: second order cuts the error 64x, first order only 8x.
  EXPECT_LT(worst, coarse_error / 16.0);
}

// ---- --below: the complement of four disks is one region with four holes ----
TEST(PatternAnalysis, BelowSegmentsTheComplement) {
  const Bumps bumps{{{0.27, 0.31, 0}, {0.71, 0.26, 0}, {0.33, 0.74, 0}, {0.68, 0.69, 0}}, 0.06};
  const double r = 0.09;
  const InputMesh mesh = square_grid(96);
  PatternAnalysisOptions options;
  options.threshold = bumps.level_of_radius(r);
  options.below = true;
  const PatternAnalysis a = analyze_pattern(mesh, sample(mesh, bumps), options);
  ASSERT_EQ(a.regions.size(), 1u);
  EXPECT_DOUBLE_EQ(a.threshold, bumps.level_of_radius(r)) << "reported in the field's own units";
  EXPECT_EQ(a.regions[0].holes, 4);
  EXPECT_TRUE(a.regions[0].touches_boundary);
  const double exact = 1.0 - 4.0 * M_PI * r * r;
  EXPECT_NEAR(a.regions[0].area, exact, 4.0 * 0.2 * std::pow(1.0 / (96 * r), 2) * M_PI * r * r);
  EXPECT_NEAR(a.regions[0].contour_length, 4.0 * 2.0 * M_PI * r, 0.01 * 4.0 * 2.0 * M_PI * r);
}

// ---- ellipses: aspect a/b, orientation theta, area pi a b, angle to a direction field ----
TEST(PatternAnalysis, EllipseHasAspectAOverBAndOrientationTheta) {
  const InputMesh mesh = square_grid(128);
  for (double theta_deg : {0.0, 30.0, 115.0}) {
    const double a = 0.22, b = 0.08, t = theta_deg * M_PI / 180.0;
    const Eigen::Vector3d c(0.5, 0.5, 0.0);
    const auto field = sample(mesh, [&](const Eigen::Vector3d& p) {
      const Eigen::Vector3d d = p - c;
      const double u = std::cos(t) * d.x() + std::sin(t) * d.y(), v = -std::sin(t) * d.x() + std::cos(t) * d.y();
      return 1.0 - (u * u) / (a * a) - (v * v) / (b * b);
    });
    FaceDirectionField direction;
    direction.mesh = mesh;
    const double d = (theta_deg + 20.0) * M_PI / 180.0;  // 20 degrees off the major axis
    direction.directions.assign(mesh.triangles.size(), Eigen::Vector3d(std::cos(d), std::sin(d), 0.0));
    PatternAnalysisOptions options;
    options.threshold = 0.0;
    options.direction = &direction;
    const PatternAnalysis result = analyze_pattern(mesh, field, options);
    ASSERT_EQ(result.regions.size(), 1u);
    const AnalysedRegion& e = result.regions[0];
    EXPECT_NEAR(e.shape.aspect_ratio, a / b, 0.01 * a / b) << theta_deg;
    EXPECT_NEAR(e.shape.orientation_deg, theta_deg, 0.3) << theta_deg;
    EXPECT_NEAR(e.area, M_PI * a * b, 0.005 * M_PI * a * b) << theta_deg;
    EXPECT_NEAR(e.shape.major_length, 2.0 * a, 0.01 * a) << "the equivalent ellipse's major diameter";
    EXPECT_NEAR(e.shape.minor_length, 2.0 * b, 0.01 * b);
    ASSERT_TRUE(e.direction_angle_deg.has_value());
    EXPECT_NEAR(*e.direction_angle_deg, 20.0, 0.3);
  }
}

// ---- a hexagonal lattice of spacing s: every neighbour pair s apart, six neighbours inside ----
TEST(PatternAnalysis, HexagonalLatticeHasSpacingS) {
  const double s = 0.2, row = s * std::sqrt(3.0) / 2.0;
  Bumps bumps{{}, 0.03};
  // Rows alternate between x = 0.05 + k s and 0.15 + k s: the outermost spots lie s/4 from the edges,
  // less than s/2, so no two spots beyond the lattice's nearest neighbours have touching cells.
  for (int j = 0; j < 5; ++j)
    for (int k = 0; k < 5; ++k) bumps.centres.emplace_back(0.05 + (j % 2) * 0.1 + k * s, 0.12 + j * row, 0.0);
  const InputMesh mesh = square_grid(100);
  const double h = 1.0 / 100;
  const PatternAnalysis a = analyse(mesh, sample(mesh, bumps), bumps.level_of_radius(0.05));
  ASSERT_EQ(a.regions.size(), 25u);
  // Hexagonal lattice 5 x 5: 3 bonds per spot minus the boundary's: 4*5 in rows + 2*4*5 - 4 between rows... counted:
  // rows: 5 x 4 = 20; between consecutive rows: 4 x 9 = 36 (each pair of rows zig-zags over 9 bonds).
  EXPECT_EQ(a.pairs.size(), 56u);
  std::vector<double> distances;
  for (const SpotPair& p : a.pairs) {
    EXPECT_NEAR(p.distance, s, h) << p.a << "-" << p.b;  // the start corner is at most ~h/sqrt(2) off the centre
    distances.push_back(p.distance);
  }
  EXPECT_NEAR(mean_and_std(distances).mean, s, 0.25 * h);
  const nlohmann::json j = pattern_analysis_json(a, "u");
  int six = 0;
  for (const auto& spot : j["spots"]) six += spot["neighbours"] == 6;
  EXPECT_EQ(six, 9) << "the 3 x 3 interior spots have six neighbours";
}

TEST(PatternAnalysis, MinAreaLeavesOutSmallerRegions) {
  // Disks of radius 0.05 and 0.1 (areas 0.00785 and 0.0314): a bound between them keeps the large one.
  const Bumps small{{{0.25, 0.25, 0}}, 0.05}, large{{{0.7, 0.7, 0}}, 0.1};
  const InputMesh mesh = square_grid(64);
  const auto field = sample(mesh, [&](const Eigen::Vector3d& p) { return small(p) + large(p); });
  PatternAnalysisOptions options;
  options.threshold = std::exp(-0.5);  // each bump's level at one sigma: radii 0.05 and 0.1
  options.min_area = 0.015;
  const PatternAnalysis a = analyze_pattern(mesh, field, options);
  ASSERT_EQ(a.regions.size(), 1u);
  EXPECT_EQ(a.dropped_regions, 1);
  EXPECT_NEAR(a.regions[0].area, M_PI * 0.01, 0.01 * M_PI * 0.01);
}

// ---- stripes: parallel bands across the square, a stadium, a ring ----
TEST(PatternAnalysis, ParallelStripesHaveWidthHalfThePeriod) {
  const double period = 0.25;
  const InputMesh mesh = square_grid(64);
  // cos > 0 on four full bands of width period / 2, centred at 0.125, 0.375, ...
  const auto field = sample(mesh, [&](const Eigen::Vector3d& p) { return std::cos(2.0 * M_PI * (p.x() - 0.125) / period); });
  const PatternAnalysis a = analyse(mesh, field, 0.0);
  ASSERT_EQ(a.regions.size(), 4u);
  for (const AnalysedRegion& r : a.regions) {
    EXPECT_TRUE(r.is_stripe);
    EXPECT_TRUE(r.touches_boundary);
    EXPECT_NEAR(r.contour_length, 2.0, 1e-9) << "two straight iso-lines across the unit square";
    ASSERT_TRUE(r.stripe_width.has_value());
    EXPECT_NEAR(*r.stripe_width, period / 2.0, 0.002);
    EXPECT_NEAR(r.shape.orientation_deg, 90.0, 1e-6);
  }
  const nlohmann::json j = pattern_analysis_json(a, "u");
  EXPECT_EQ(j["stripe_count"], 4);
  EXPECT_EQ(j["spot_count"], 0);
  EXPECT_NEAR(j["stripe_width"]["mean"].get<double>(), period / 2.0, 0.002);
}

TEST(PatternAnalysis, IsolatedBandAndRingHaveWidthW) {
  const InputMesh mesh = square_grid(160);
  const double w = 0.08;
  // A stadium: points within w/2 of the segment (0.25, 0.5)-(0.75, 0.5).
  const auto stadium = sample(mesh, [&](const Eigen::Vector3d& p) {
    const double x = std::clamp(p.x(), 0.25, 0.75);
    return w / 2.0 - std::hypot(p.x() - x, p.y() - 0.5);
  });
  PatternAnalysis a = analyse(mesh, stadium, 0.0);
  ASSERT_EQ(a.regions.size(), 1u);
  EXPECT_TRUE(a.regions[0].is_stripe);
  EXPECT_FALSE(a.regions[0].touches_boundary);
  ASSERT_TRUE(a.regions[0].stripe_width.has_value());
  EXPECT_NEAR(*a.regions[0].stripe_width, w, 0.01 * w);
  // A ring of radius 0.3: a hole, so a stripe whatever its aspect (1 here).
  const auto ring = sample(mesh, [&](const Eigen::Vector3d& p) {
    return w / 2.0 - std::abs(std::hypot(p.x() - 0.5, p.y() - 0.5) - 0.3);
  });
  a = analyse(mesh, ring, 0.0);
  ASSERT_EQ(a.regions.size(), 1u);
  EXPECT_EQ(a.regions[0].holes, 1);
  EXPECT_TRUE(a.regions[0].is_stripe);
  EXPECT_NEAR(a.regions[0].shape.aspect_ratio, 1.0, 0.01);
  ASSERT_TRUE(a.regions[0].stripe_width.has_value());
  EXPECT_NEAR(*a.regions[0].stripe_width, w, 0.01 * w);
}

// ---- caps on the unit sphere: area 2 pi (1 - cos rho), octahedral spacing pi / 2 ----
TEST(PatternAnalysis, SphereCapsHaveCapAreaAndGeodesicSpacing) {
  const InputMesh mesh = load_mesh("shape:sphere");
  const std::vector<Eigen::Vector3d> centres = {Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                                -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()};
  const double rho = 0.45;
  // cos of the angle to the nearest centre: > cos rho exactly on the caps of geodesic radius rho.
  const auto field = sample(mesh, [&](const Eigen::Vector3d& p) {
    double best = -1.0;
    for (const Eigen::Vector3d& c : centres) best = std::max(best, p.normalized().dot(c));
    return best;
  });
  const PatternAnalysis a = analyse(mesh, field, std::cos(rho));
  ASSERT_EQ(a.regions.size(), 6u);
  const double cap = 2.0 * M_PI * (1.0 - std::cos(rho));
  for (const AnalysedRegion& r : a.regions) {
    // The mesh is inscribed in the sphere: its chords shrink areas by O(h^2), 0.3 % at this level.
    EXPECT_NEAR(r.area, cap, 0.01 * cap);
    EXPECT_NEAR(r.shape.aspect_ratio, 1.0, 0.03);
    EXPECT_NEAR(r.shape.centre.norm(), 1.0, 0.01) << "the centre lies on the surface, not inside the sphere";
  }
  // Octahedron: each cap touches the four around it, not the opposite one: 12 pairs, pi/2 apart.
  ASSERT_EQ(a.pairs.size(), 12u);
  for (const SpotPair& p : a.pairs) EXPECT_NEAR(p.distance, M_PI / 2.0, 0.03 * M_PI / 2.0);
}

TEST(PatternAnalysis, DefaultThresholdIsMeanPlusHalfStd) {
  // A field linear in x on the unit square: area-weighted mean 1/2, std 1/sqrt(12).
  const InputMesh mesh = square_grid(40);
  const auto field = sample(mesh, [](const Eigen::Vector3d& p) { return p.x(); });
  // Lumped masses are exact for the mean of a linear field; the variance by lumping is within O(h^2).
  EXPECT_NEAR(default_pattern_threshold(mesh, field), 0.5 + 0.5 / std::sqrt(12.0), 1e-3);
}

TEST(PatternAnalysis, ConstantFieldIsAnErrorThatSaysSo) {
  const InputMesh mesh = square_grid(8);
  const std::string message = testing::input_error_of(
      [&] { analyze_pattern(mesh, InputVertexData<double>(mesh.positions.size(), 2.0), PatternAnalysisOptions{}); });
  EXPECT_NE(message.find("nothing to segment"), std::string::npos) << message;
  EXPECT_NE(message.find("constant"), std::string::npos) << message;
}

TEST(PatternAnalysis, HistogramCountsEveryValueInSturgesBins) {
  const Histogram h = make_histogram({1, 2, 2, 3, 3, 3, 4, 4, 4, 4, NAN});
  ASSERT_EQ(h.counts.size(), 5u);  // n = 10 finite: ceil(log2 10) + 1
  EXPECT_EQ(h.counts, (std::vector<int>{1, 2, 0, 3, 4}));  // bins of width 0.6 from 1 to 4
  EXPECT_DOUBLE_EQ(h.edges.front(), 1.0);
  EXPECT_DOUBLE_EQ(h.edges.back(), 4.0);
  const Histogram same = make_histogram({2.0, 2.0, 2.0});  // one value: a drawable range around it
  EXPECT_EQ(same.counts, (std::vector<int>{0, 3, 0}));
  EXPECT_DOUBLE_EQ(same.edges.front(), 1.9);
  EXPECT_DOUBLE_EQ(same.edges.back(), 2.1);
}

// The summary's interior_spot_area leaves out a spot cut by the boundary (its area is a piece of a
// spot's): three bumps of radius 0.1, one centred on the square's edge, give three areas but two
// interior ones, each pi 0.01. The spacing's median is that of the neighbouring pairs' distances.
TEST(PatternAnalysis, InteriorSpotAreasLeaveOutSpotsCutByTheBoundary) {
  const InputMesh mesh = square_grid(64);
  const Bumps bumps{{{0.3, 0.3, 0}, {0.7, 0.7, 0}, {0.0, 0.6, 0}}, 0.05};
  const PatternAnalysis a = analyse(mesh, sample(mesh, bumps), bumps.level_of_radius(0.1));
  const nlohmann::json j = pattern_analysis_json(a, "v");
  EXPECT_EQ(j["summary"]["area"]["count"], 3);
  EXPECT_EQ(j["summary"]["interior_spot_area"]["count"], 2);
  EXPECT_NEAR(j["summary"]["interior_spot_area"]["median"].get<double>(), M_PI * 0.01, 0.02 * M_PI * 0.01);
  std::vector<double> d;
  for (const SpotPair& p : a.pairs) d.push_back(p.distance);
  std::sort(d.begin(), d.end());
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(j["spacing"]["median"].get<double>(), d[1]);
}

// ---- the command on a run folder ----
TEST(PatternAnalysisCli, AnalyzesARunFolderAndWritesJsonAndHistograms) {
  TempDir dir;
  const InputMesh mesh = square_grid(64);
  const Bumps bumps{{{0.3, 0.3, 0}, {0.7, 0.7, 0}}, 0.05};
  const InputVertexData<double> v = sample(mesh, bumps);
  const InputVertexData<double> flat(mesh.positions.size(), 1.0);
  write_fields_ply((dir.path / "fields_full.ply").string(), mesh, {{"pheromone", flat}, {"v", v}}, {}, "test");
  std::ofstream(dir.path / "run.json") << R"({"preview_morphogen": "v"})";

  const auto ok = run_physarum("analyze " + testing::quoted(dir.path) + " --threshold " + std::to_string(bumps.level_of_radius(0.1)));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  std::ifstream in(dir.path / "analysis.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["field"], "v") << "run.json's preview_morphogen is the default field";
  EXPECT_EQ(j["spot_count"], 2);
  EXPECT_NEAR(j["spots"][0]["area"].get<double>(), M_PI * 0.01, 0.01 * M_PI * 0.01);  // float PLY positions
  EXPECT_NEAR(j["spacing"]["mean"].get<double>(), std::sqrt(0.32), 1.0 / 64);
  for (const char* key : {"threshold", "spots", "spacing", "stripe_width", "summary"}) EXPECT_TRUE(j.contains(key)) << key;
  auto png = OIIO::ImageInput::open((dir.path / "analysis.png").string());
  ASSERT_TRUE(png);
  EXPECT_EQ(png->spec().width, 1800);
  EXPECT_EQ(png->spec().height, 420);

  // Errors name the problem and write nothing.
  TempDir out;
  const auto constant = run_physarum("analyze " + testing::quoted(dir.path) + " --field pheromone --out " + testing::quoted(out.path / "x"));
  EXPECT_EQ(constant.exit_code, 1);
  EXPECT_NE(constant.err.find("constant"), std::string::npos) << constant.err;
  EXPECT_FALSE(std::filesystem::exists(out.path / "x"));
  const auto missing_field = run_physarum("analyze " + testing::quoted(dir.path) + " --field w");
  EXPECT_EQ(missing_field.exit_code, 1);
  EXPECT_NE(missing_field.err.find("no vertex property 'w'"), std::string::npos) << missing_field.err;
  const auto missing_dir = run_physarum("analyze " + testing::quoted(dir.path / "nope"));
  EXPECT_EQ(missing_dir.exit_code, 1);
  EXPECT_NE(missing_dir.err.find("no such folder"), std::string::npos) << missing_dir.err;
}

}  // namespace
}  // namespace physarum
