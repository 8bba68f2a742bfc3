// The heat method (common/map_tools/heat_geodesic.hpp) against distances known in closed form: great circles
// on the unit icosphere (error within 1 % of pi at shape:sphere's resolution, and falling as the
// sphere is refined; the seed's first ring; a region of seeds), Euclidean distance on the flat square from a corner and on the disk from its
// centre (surfaces with boundary: the Neumann/Dirichlet average), and |grad distance| = 1 away from
// the source and the cut locus.
#include "common/base/errors.hpp"
#include "common/surface/fe_operators.hpp"
#include "common/map_tools/heat_geodesic.hpp"
#include "common/setup/scene_surface.hpp"
#include "geodesic_test_support.hpp"
#include "map_tool_meshes.hpp"
#include "pheromone_test_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace physarum {
namespace {

using testing::great_circle;
using testing::max_error;

PreparedSurface unscaled(const std::string& mesh) { return prepare_surface(SurfaceSpec{mesh, std::nullopt, std::nullopt, 0.0}); }

// The issue asks for 1 % of pi at shape:sphere's resolution (level 4, h = 0.075). Measured 0.51 /
// 0.76 / 0.74 % for these sources (0.93-1.09 % before the faces around the seed took the cone's own
// gradient: heat_geodesic.cpp), the largest errors at the antipode (the cut locus); one level finer
// 0.39 / 0.51 / 0.60 %.
TEST(HeatGeodesic, GreatCircleDistanceOnTheIcosphereWithinOnePercentOfPi) {
  const PreparedSurface s = unscaled("shape:sphere");  // level 4: 2562 vertices, no refinement
  ASSERT_EQ(s.domain.vertex_count, s.input.vertex_count());
  const HeatGeodesicSolver heat(s.domain);
  for (const int source : {0, 100, 2000}) {
    const int seed = s.input_to_intrinsic[static_cast<size_t>(source)];
    const IntrinsicVertexData<double> d = heat.distance({seed});
    const Eigen::Vector3d p = s.input.positions[static_cast<size_t>(source)];
    double worst = 0.0;
    for (int v = 0; v < s.input.vertex_count(); ++v)
      worst = std::max(worst, std::abs(d[static_cast<size_t>(s.input_to_intrinsic[static_cast<size_t>(v)])] -
                                       great_circle(p, s.input.positions[static_cast<size_t>(v)])));
    EXPECT_LT(worst, 0.01 * std::numbers::pi) << "source " << source;
    EXPECT_EQ(d[static_cast<size_t>(seed)], 0.0);
  }
}

TEST(HeatGeodesic, FirstRingAroundASeedSitsAtItsGreatCircleDistance) {
  // The distance is a cone at a point seed; a unit field alone leaves the first ring short of it by
  // about (1 - cos(theta/2)) h = 0.13 h on an equilateral fan, and every farther vertex with it. With
  // the seed's faces carrying the cone's interpolant the ring is unbiased: its mean error within
  // 0.02 h, each vertex within 0.1 h (phi still fits the faces beyond the ring in least squares).
  const InputMesh mesh = testing::make_icosphere(4);
  const SurfaceDomain domain = testing::make_domain(mesh);
  const HeatGeodesicSolver heat(domain);
  const double h = heat.mean_edge_length();
  for (const int source : {0, 100, 2000}) {
    const IntrinsicVertexData<double> d = heat.distance({source});
    double sum = 0.0;
    int ring = 0;
    for (int f = 0; f < domain.face_count; ++f)
      for (int k = 0; k < 3; ++k) {
        if (domain.face_vertices[f][k] != source) continue;
        const int w = domain.face_vertices[f][(k + 1) % 3];  // each neighbour once: the fan's next corner
        const double error = d[static_cast<size_t>(w)] - great_circle(mesh.positions[static_cast<size_t>(source)], mesh.positions[static_cast<size_t>(w)]);
        EXPECT_LT(std::abs(error), 0.1 * h) << "source " << source << " neighbour " << w;
        sum += error;
        ++ring;
      }
    ASSERT_GE(ring, 5) << "source " << source;
    EXPECT_LT(std::abs(sum / ring), 0.02 * h) << "source " << source;
  }
}

TEST(HeatGeodesic, DistanceFromASeedRegionIsZeroInsideAndGrowsFromItsRim) {
  // Every vertex of a spherical cap (radius 0.5 about vertex 0) is a seed: the distance is 0 on the
  // cap and the great-circle distance to its rim outside (the cap's seeds lie on its rim's circle up
  // to one edge, so the exact distance from the nearest seed is r - r_rim within h, r_rim the largest
  // seed radius). Without care the cap's interior faces, where the heat still flows outward from the
  // cap's centre, made it the distance from the centre (0.47 on the outermost seeds).
  const InputMesh mesh = testing::make_icosphere(4);
  const SurfaceDomain domain = testing::make_domain(mesh);
  const HeatGeodesicSolver heat(domain);
  const Eigen::Vector3d centre = mesh.positions[0];
  std::vector<int> cap;
  double rim = 0.0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const double r = great_circle(centre, mesh.positions[static_cast<size_t>(v)]);
    if (r < 0.5) {
      cap.push_back(v);
      rim = std::max(rim, r);
    }
  }
  ASSERT_GT(cap.size(), 100u);
  const IntrinsicVertexData<double> d = heat.distance(cap);
  for (const int v : cap) EXPECT_LT(d[static_cast<size_t>(v)], 0.25 * heat.mean_edge_length()) << "seed " << v;
  EXPECT_LT(max_error(mesh, d, [&](const Eigen::Vector3d& q) { return std::max(0.0, great_circle(centre, q) - rim); }),
            heat.mean_edge_length());
}

// Heat decays about e-fold per edge, and one solve resolves 440 decades (~1000 edges): a strip
// 3000 cells long seeded along one short side needs three levels. The distance there is x; without
// the levels (or with a wrong rescaling between them) the far two thirds get no direction.
TEST(HeatGeodesic, DistanceAlongAStripLongerThanOneSolveResolves) {
  const InputMesh strip = testing::make_flat_rectangle(0.0, 3000.0, 0.0, 2.0, 3000, 2);
  const SurfaceDomain domain = testing::make_domain(strip);
  std::vector<int> short_side;
  for (int v = 0; v < strip.vertex_count(); ++v)
    if (strip.positions[static_cast<size_t>(v)].x() == 0.0) short_side.push_back(v);
  ASSERT_EQ(short_side.size(), 3u);
  const IntrinsicVertexData<double> d = HeatGeodesicSolver(domain).distance(short_side);
  // Measured 7.6 (0.25 % of the length; the issue asks 2 % for flat distances). One level: 1830.
  EXPECT_LT(testing::max_error(strip, d, [](const Eigen::Vector3d& q) { return q.x(); }), 0.005 * 3000.0);
}

TEST(HeatGeodesic, SphereErrorFallsUnderRefinement) {
  double previous = std::numeric_limits<double>::infinity();
  for (const int level : {3, 4, 5}) {
    const InputMesh mesh = testing::make_icosphere(level);
    const SurfaceDomain domain = testing::make_domain(mesh);
    const IntrinsicVertexData<double> d = HeatGeodesicSolver(domain).distance({0});
    const double error = max_error(mesh, d, [&](const Eigen::Vector3d& q) { return great_circle(mesh.positions[0], q); });
    EXPECT_LT(error, previous) << "level " << level;
    previous = error;
  }
}

TEST(HeatGeodesic, EuclideanDistanceOnTheSquareFromACornerWithinTwoPercent) {
  // shape:square is the unit square in z = 0; the corner at the origin is a boundary seed.
  const PreparedSurface s = unscaled("shape:square");
  int corner = -1;
  for (int v = 0; v < s.input.vertex_count(); ++v)
    if (s.input.positions[static_cast<size_t>(v)].norm() < 1e-12) corner = s.input_to_intrinsic[static_cast<size_t>(v)];
  ASSERT_GE(corner, 0);
  const HeatGeodesicSolver heat(s.domain);
  EXPECT_TRUE(heat.has_boundary());
  const IntrinsicVertexData<double> d = heat.distance({corner});
  double worst = 0.0;
  for (int v = 0; v < s.input.vertex_count(); ++v)
    worst = std::max(worst, std::abs(d[static_cast<size_t>(s.input_to_intrinsic[static_cast<size_t>(v)])] -
                                     s.input.positions[static_cast<size_t>(v)].norm()));
  // The issue asks for 2 % (of the largest distance, the diagonal sqrt 2); measured 0.95 %. With the
  // seed on the boundary the heat is the Neumann solution alone, which turns the level sets to meet
  // the far sides square; without the outflow extrapolation there (common/map_tools/boundary_outflow.hpp) the
  // error was 2.45 % (-2.3 % at the corner (1, 0), +2.4 % near the far corner).
  EXPECT_LT(worst, 0.02 * std::sqrt(2.0));
}

// Boundary seeds other than a corner: the middle of a side (Euclidean distance) and a whole side
// (distance = y). Before the outflow extrapolation (and with the Dirichlet average that held the
// seeds at their Neumann values) 1.21 % and 2.88 % of the largest distance.
TEST(HeatGeodesic, DistanceFromTheMiddleOfASideAndFromAWholeSideOfTheSquare) {
  const PreparedSurface s = unscaled("shape:square");
  const HeatGeodesicSolver heat(s.domain);
  std::vector<int> middle, side;
  for (int v = 0; v < s.input.vertex_count(); ++v) {
    const Eigen::Vector3d& p = s.input.positions[static_cast<size_t>(v)];
    if (p.y() == 0.0) side.push_back(s.input_to_intrinsic[static_cast<size_t>(v)]);
    if (p.y() == 0.0 && p.x() == 0.5) middle.push_back(s.input_to_intrinsic[static_cast<size_t>(v)]);
  }
  ASSERT_EQ(middle.size(), 1u);
  auto worst_error = [&](const std::vector<int>& seeds, auto exact) {
    const IntrinsicVertexData<double> d = heat.distance(seeds);
    double worst = 0.0;
    for (int v = 0; v < s.input.vertex_count(); ++v)
      worst = std::max(worst, std::abs(d[static_cast<size_t>(s.input_to_intrinsic[static_cast<size_t>(v)])] -
                                       exact(s.input.positions[static_cast<size_t>(v)])));
    return worst;
  };
  const double from_middle = worst_error(middle, [](const Eigen::Vector3d& p) { return (p - Eigen::Vector3d(0.5, 0, 0)).norm(); });
  EXPECT_LT(from_middle, 0.01 * std::sqrt(1.25));  // measured 0.81 %
  const double from_side = worst_error(side, [](const Eigen::Vector3d& p) { return p.y(); });
  EXPECT_LT(from_side, 0.01);  // measured 0.61 %
}

TEST(HeatGeodesic, DistanceFromTheDiskCentreIsTheRadius) {
  // An interior seed on a surface with boundary: the average of the Neumann and Dirichlet heat.
  const PreparedSurface s = unscaled("shape:disk");
  int centre = -1;
  for (int v = 0; v < s.input.vertex_count(); ++v)
    if (s.input.positions[static_cast<size_t>(v)].norm() < 1e-12) centre = s.input_to_intrinsic[static_cast<size_t>(v)];
  ASSERT_GE(centre, 0);
  const IntrinsicVertexData<double> d = HeatGeodesicSolver(s.domain).distance({centre});
  double worst = 0.0;
  for (int v = 0; v < s.input.vertex_count(); ++v)
    worst = std::max(worst, std::abs(d[static_cast<size_t>(s.input_to_intrinsic[static_cast<size_t>(v)])] -
                                     s.input.positions[static_cast<size_t>(v)].norm()));
  EXPECT_LT(worst, 0.005);  // 0.5 % of the radius (measured 0.24 %; 0.88 % before the seed's faces took the cone)
}

TEST(HeatGeodesic, GradientHasUnitLengthAwayFromSourceAndCutLocus) {
  const InputMesh mesh = testing::make_icosphere(5);
  const SurfaceDomain domain = testing::make_domain(mesh);
  testing::expect_unit_gradient_away_from_source_and_cut_locus(mesh, domain, HeatGeodesicSolver(domain).distance({0}));
}

TEST(HeatGeodesic, RefusesBadSeeds) {
  const SurfaceDomain domain = testing::make_domain(testing::make_icosphere(1));
  const HeatGeodesicSolver heat(domain);
  EXPECT_NE(testing::input_error_of([&] { heat.distance({}); }).find("empty"), std::string::npos);
  EXPECT_NE(testing::input_error_of([&] { heat.distance({domain.vertex_count}); }).find("no intrinsic vertex"),
            std::string::npos);
  EXPECT_THROW(HeatGeodesicSolver(domain, 0.0), std::invalid_argument);
}

TEST(HeatGeodesic, EveryPieceNeedsASeed) {
  // Two icospheres side by side: one seed leaves the other piece at an infinite distance.
  InputMesh two = testing::make_icosphere(1);
  const InputMesh other = testing::make_icosphere(1);
  const int offset = two.vertex_count();
  for (const auto& p : other.positions) two.positions.push_back(p + Eigen::Vector3d(3.0, 0.0, 0.0));
  for (const auto& t : other.triangles) two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const SurfaceDomain domain = testing::make_domain(two);
  const HeatGeodesicSolver heat(domain);
  EXPECT_NE(testing::input_error_of([&] { heat.distance({0}); }).find("separate pieces"), std::string::npos);
  // One seed on each: each sphere gets its own distance (icosphere level 1 vertex 0 to itself is 0).
  const IntrinsicVertexData<double> d = heat.distance({0, offset});
  EXPECT_EQ(d[0], 0.0);
  EXPECT_EQ(d[static_cast<size_t>(offset)], 0.0);
  for (int v = 0; v < offset; ++v) EXPECT_NEAR(d[static_cast<size_t>(v)], d[static_cast<size_t>(v + offset)], 1e-9);
}

}  // namespace
}  // namespace physarum
