// Fast marching (common/map_tools/fast_marching.hpp) against distances known in closed form: Euclidean
// distance from a corner of the flat square (exact up to rounding: every update is a two-point
// update through a right or acute corner), from a vertex of a flat mesh full of obtuse triangles
// (exact only because the obtuse corners are split by unfolding), great circles on the unit
// icosphere (within 0.5 % of pi at the default resolution, falling with refinement), and
// |grad distance| = 1 away from the source and cut locus.
#include "common/base/errors.hpp"
#include "common/map_tools/fast_marching.hpp"
#include "common/surface/fe_operators.hpp"
#include "common/setup/scene_surface.hpp"
#include "geodesic_test_support.hpp"
#include "pheromone_test_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace physarum {
namespace {

using testing::great_circle;
using testing::max_error;

TEST(FastMarching, EuclideanDistanceOnTheSquareFromACorner) {
  const PreparedSurface s = prepare_surface(SurfaceSpec{"shape:square", std::nullopt, std::nullopt, 0.0});
  int corner = -1;
  for (int v = 0; v < s.input.vertex_count(); ++v)
    if (s.input.positions[static_cast<size_t>(v)].norm() < 1e-12) corner = s.input_to_intrinsic[static_cast<size_t>(v)];
  ASSERT_GE(corner, 0);
  const IntrinsicVertexData<double> d = FastMarchingGeodesics(s.domain).distance({corner});
  for (int v = 0; v < s.input.vertex_count(); ++v) {
    const double exact = s.input.positions[static_cast<size_t>(v)].norm();
    EXPECT_NEAR(d[static_cast<size_t>(s.input_to_intrinsic[static_cast<size_t>(v)])], exact, 1e-3 * exact) << "vertex " << v;
  }
}

TEST(FastMarching, ObtuseTrianglesAreSplitByUnfoldingAndStayExactOnAFlatMesh) {
  // A 24 x 24 flat grid with interior vertices jittered by up to 0.35 cells, taken as it is (no
  // Delaunay flips): many obtuse corners. From a vertex in the middle every vertex is reached
  // through acute or split corners, so the distance is the straight line.
  const InputMesh mesh = testing::make_square_grid(24, true, 0.35, 7);
  const SurfaceDomain domain = testing::make_domain(mesh);
  const FastMarchingGeodesics marching(domain);
  ASSERT_GT(marching.obtuse_corner_count(), 50);
  // Near the boundary the strip may run out of faces; everywhere else the unfolding succeeds.
  EXPECT_GT(marching.split_corner_count(), marching.obtuse_corner_count() * 9 / 10);
  const int source = 12 * 25 + 12;
  const IntrinsicVertexData<double> d = marching.distance({source});
  const Eigen::Vector3d p = mesh.positions[static_cast<size_t>(source)];
  int exact_count = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const double exact = (mesh.positions[static_cast<size_t>(v)] - p).norm();
    const double got = d[static_cast<size_t>(v)];
    // Never shorter than the straight line (every update is the length of a path in the plane)...
    EXPECT_GE(got, exact - 1e-12) << "vertex " << v;
    // ...and equal to it wherever no unsplit obtuse corner is in the way: all but a few boundary vertices.
    if (std::abs(got - exact) <= 1e-9 * std::max(exact, 1.0)) ++exact_count;
  }
  EXPECT_GE(exact_count, mesh.vertex_count() * 95 / 100);
  EXPECT_LT(max_error(mesh, d, [&](const Eigen::Vector3d& q) { return (q - p).norm(); }), 1e-3);
}

// Largest |fast marching - arccos(p.q)| over the vertices of the unit sphere `mesh` (taken as it is:
// intrinsic vertex v on input vertex v) from input vertex `source`.
double great_circle_error(const InputMesh& mesh, const FastMarchingGeodesics& marching, int source) {
  const IntrinsicVertexData<double> d = marching.distance({source});
  return max_error(mesh, d, [&](const Eigen::Vector3d& q) { return great_circle(mesh.positions[static_cast<size_t>(source)], q); });
}

// The target: 0.5 % of pi at shape:sphere's resolution (icosphere level 4, h = 0.075). A
// point-source update alone is first order here (1.0-1.3 % at level 4: past the equator the fronts
// converge, which a per-triangle point source cannot represent); tracking each vertex's source
// through the unfoldings gives the polyhedron's own geodesics, whose gap to the great circles (chord
// against arc) is second order, so the error also has to fall as the sphere is refined.
TEST(FastMarching, GreatCircleDistanceOnTheIcosphereWithinHalfAPercentOfPi) {
  const PreparedSurface s = prepare_surface(SurfaceSpec{"shape:sphere", std::nullopt, std::nullopt, 0.0});
  ASSERT_EQ(s.input.vertex_count(), 2562);  // level 4
  const FastMarchingGeodesics marching(s.domain);
  for (const int source : {0, 100, 2000}) {
    const int seed = s.input_to_intrinsic[static_cast<size_t>(source)];
    const IntrinsicVertexData<double> d = marching.distance({seed});
    const Eigen::Vector3d p = s.input.positions[static_cast<size_t>(source)];
    double worst = 0.0;
    for (int v = 0; v < s.input.vertex_count(); ++v)
      worst = std::max(worst, std::abs(d[static_cast<size_t>(s.input_to_intrinsic[static_cast<size_t>(v)])] -
                                       great_circle(p, s.input.positions[static_cast<size_t>(v)])));
    EXPECT_LT(worst, 0.005 * std::numbers::pi) << "source " << source;
  }
}

TEST(FastMarching, GreatCircleErrorFallsAsTheIcosphereIsRefined) {
  const std::array<int, 3> sources{0, 100, 2000};
  std::array<double, 3> coarser;
  coarser.fill(std::numeric_limits<double>::infinity());
  for (const int level : {4, 5, 6}) {
    const InputMesh mesh = testing::make_icosphere(level);
    const SurfaceDomain domain = testing::make_domain(mesh);
    const FastMarchingGeodesics marching(domain);
    for (size_t i = 0; i < sources.size(); ++i) {
      const double error = great_circle_error(mesh, marching, sources[i]);
      EXPECT_LT(error, coarser[i]) << "source " << sources[i] << ", level " << level;
      coarser[i] = error;
    }
  }
}

// No path between two points is shorter than the straight line through space. A real mesh has
// saddles and sharp convex vertices, where a straight line drawn from a reconstructed (virtual)
// source, or past a saddle's far side, would be a shortcut: unfolding estimates' sources made
// values up to 1.4 % of the diameter shorter than the chord on spot. What is left (0.18 % of the
// diameter on spot from vertex 1465, none on cow) comes from a tracked source being used for
// lines that enter the vertex's star away from the point its own line came through, where the
// faces behind differ; the bound states that margin.
TEST(FastMarching, NeverShorterThanTheStraightLineThroughSpaceOnRealMeshes) {
  for (const char* name : {"spot.obj", "cow.obj"}) {
    PHYSARUM_REQUIRE_SHARED_MESH(path, name);
    const PreparedSurface s = prepare_surface(SurfaceSpec{path, std::nullopt, std::nullopt, 0.0});
    const FastMarchingGeodesics marching(s.domain);
    for (const int source : {0, s.input.vertex_count() / 2}) {
      const IntrinsicVertexData<double> d = marching.distance({s.input_to_intrinsic[static_cast<size_t>(source)]});
      const Eigen::Vector3d p = s.simulated.positions[static_cast<size_t>(source)];
      double shortest_margin = 0.0;
      for (int v = 0; v < s.input.vertex_count(); ++v)
        shortest_margin = std::min(shortest_margin, d[static_cast<size_t>(s.input_to_intrinsic[static_cast<size_t>(v)])] -
                                                        (s.simulated.positions[static_cast<size_t>(v)] - p).norm());
      EXPECT_GE(shortest_margin, -0.003 * s.diameter) << name << ", source " << source;
    }
  }
}

TEST(FastMarching, GradientHasUnitLengthAwayFromSourceAndCutLocus) {
  const InputMesh mesh = testing::make_icosphere(5);
  const SurfaceDomain domain = testing::make_domain(mesh);
  testing::expect_unit_gradient_away_from_source_and_cut_locus(mesh, domain, FastMarchingGeodesics(domain).distance({0}));
}

TEST(FastMarching, TwoSeedsGiveTheNearerOne) {
  // Flat square, seeds at two opposite corners: min of the two Euclidean distances.
  const InputMesh mesh = testing::make_square_grid(16, true);
  const SurfaceDomain domain = testing::make_domain(mesh);
  const int far_corner = mesh.vertex_count() - 1;
  const IntrinsicVertexData<double> d = FastMarchingGeodesics(domain).distance({0, far_corner});
  const double error = max_error(mesh, d, [](const Eigen::Vector3d& q) {
    return std::min(q.norm(), (q - Eigen::Vector3d(1.0, 1.0, 0.0)).norm());
  });
  EXPECT_LT(error, 1e-3);
}

TEST(FastMarching, RefusesBadSeeds) {
  const SurfaceDomain domain = testing::make_domain(testing::make_icosphere(1));
  const FastMarchingGeodesics marching(domain);
  EXPECT_NE(testing::input_error_of([&] { marching.distance({}); }).find("empty"), std::string::npos);
  EXPECT_NE(testing::input_error_of([&] { marching.distance({-1}); }).find("no intrinsic vertex"), std::string::npos);
}

}  // namespace
}  // namespace physarum
