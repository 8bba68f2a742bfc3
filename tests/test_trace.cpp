// Straight-line walks across face frames: exact answers on flat and developable surfaces
// (Euclidean segments, mirror images, a closed loop around a prism), boundary rules, degenerate
// starts and headings, and robustness on a closed curved surface.
#include "common/mesh/input_mesh.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/surface/trace.hpp"
#include "pheromone_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

namespace physarum {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// The side of a regular octagonal prism (circumradius 1, height h): an open band, flat when unrolled.
constexpr int kSides = 8;
Vector3d octagon_corner(int k, double z) {
  const double a = 2.0 * std::numbers::pi * k / kSides;
  return {std::cos(a), std::sin(a), z};
}
InputMesh octagonal_band(double height) {
  InputMesh m;
  m.source = "test:prism";
  for (int k = 0; k < kSides; ++k) {
    m.positions.push_back(octagon_corner(k, 0.0));
    m.positions.push_back(octagon_corner(k, height));
  }
  for (int k = 0; k < kSides; ++k) {
    const int a = 2 * k, b = 2 * ((k + 1) % kSides), c = b + 1, d = a + 1;  // outward-facing
    m.triangles.push_back({a, b, c});
    m.triangles.push_back({a, c, d});
  }
  return m;
}
const double kSideLength = 2.0 * std::sin(std::numbers::pi / kSides);
// Point of the band at arc length s (from corner 0, counter-clockwise) and height z.
Vector3d band_point(double s, double z) {
  s = std::fmod(s, kSides * kSideLength);
  if (s < 0) s += kSides * kSideLength;
  const int k = std::min(static_cast<int>(s / kSideLength), kSides - 1);
  const double t = (s - k * kSideLength) / kSideLength;
  return (1.0 - t) * octagon_corner(k, z) + t * octagon_corner(k + 1, z);
}

// The rigid map between face f's 2D frame and 3D, for domains built from an extrinsic mesh.
struct FaceFrame {
  Vector3d origin, ex, ey;
  FaceFrame(const InputMesh& m, int f) {
    const Vector3d& p0 = m.positions[m.triangles[f][0]];
    const Vector3d& p1 = m.positions[m.triangles[f][1]];
    const Vector3d& p2 = m.positions[m.triangles[f][2]];
    origin = p0;
    ex = (p1 - p0).normalized();
    ey = (p1 - p0).cross(p2 - p0).normalized().cross(ex);
  }
  Vector3d point(const Vector2d& p) const { return origin + p.x() * ex + p.y() * ey; }
  Vector3d direction(const Vector2d& d) const { return d.x() * ex + d.y() * ey; }
  Vector2d local(const Vector3d& p) const { return {(p - origin).dot(ex), (p - origin).dot(ey)}; }
  Vector2d local_direction(const Vector3d& d) const { return {d.dot(ex), d.dot(ey)}; }
};

// Face containing a 3D point of the mesh (by barycentric coordinates in each face frame).
int locate(const InputMesh& m, const SurfaceDomain& d, const Vector3d& p) {
  for (int f = 0; f < d.face_count; ++f) {
    const FaceFrame frame(m, f);
    if (std::abs((p - frame.origin).dot(frame.ex.cross(frame.ey))) > 1e-12) continue;
    if (barycentric_in_face(d, f, frame.local(p)).minCoeff() >= -1e-12) return f;
  }
  return -1;
}

bool inside_face(const SurfaceDomain& d, int f, const Vector2d& p, double tol = 1e-12) {
  return f >= 0 && f < d.face_count && barycentric_in_face(d, f, p).minCoeff() >= -tol;
}

struct Walk {
  TraceResult result;
  Vector3d end;
  Vector3d heading;
  double segment_length = 0.0;
};

// Traces from a 3D point along a 3D direction and checks the invariants every trace must satisfy.
Walk walk(const InputMesh& m, const SurfaceDomain& d, const Vector3d& start, const Vector3d& heading, double length,
          BoundaryRule rule) {
  const int f = locate(m, d, start);
  EXPECT_GE(f, 0) << "start point not on the mesh";
  const FaceFrame frame(m, f);
  std::vector<TraceSegment> segments;
  Walk w;
  w.result = trace(d, f, frame.local(start), frame.local_direction(heading), length, rule, &segments);
  const FaceFrame end_frame(m, w.result.face);
  w.end = end_frame.point(w.result.position);
  w.heading = end_frame.direction(w.result.heading);
  EXPECT_TRUE(inside_face(d, w.result.face, w.result.position)) << "end point outside its face";
  EXPECT_NEAR(w.result.heading.norm(), 1.0, 1e-12);
  EXPECT_FALSE(segments.empty());
  // Segments lie in their faces, join up in 3D, and their lengths add up to the walked length.
  Vector3d previous_end = start;
  for (const TraceSegment& s : segments) {
    EXPECT_TRUE(inside_face(d, s.face, s.start, 1e-9));
    EXPECT_TRUE(inside_face(d, s.face, s.end, 1e-9));
    const FaceFrame sf(m, s.face);
    EXPECT_LT((sf.point(s.start) - previous_end).norm(), 1e-9);
    previous_end = sf.point(s.end);
    w.segment_length += (s.end - s.start).norm();
  }
  EXPECT_EQ(segments.back().face, w.result.face);
  EXPECT_LT((previous_end - w.end).norm(), 1e-9);
  EXPECT_NEAR(w.segment_length, w.result.length, 1e-12 * std::max(1.0, length));
  return w;
}

Vector3d planar(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }

TEST(Trace, StraightWalkOnAFlatSquareIsTheEuclideanSegment) {
  const InputMesh m = testing::make_square_grid(4, true);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
  const Vector3d start(0.3, 0.2, 0.0);
  for (double angle : {0.0, 0.7, 1.9, 3.0, 4.4, 5.9}) {
    const double length = 0.15;  // stays inside the square from this start in every direction
    const Walk w = walk(m, d, start, planar(angle), length, BoundaryRule::Reflect);
    EXPECT_LT((w.end - (start + length * planar(angle))).norm(), 1e-13) << "angle " << angle;
    EXPECT_LT((w.heading - planar(angle)).norm(), 1e-13);
    EXPECT_DOUBLE_EQ(w.result.length, length);
    EXPECT_FALSE(w.result.hit_boundary);
  }
  // A long diagonal walk crossing many faces.
  const Walk w = walk(m, d, start, planar(0.7), 0.9, BoundaryRule::Reflect);
  EXPECT_LT((w.end - (start + 0.9 * planar(0.7))).norm(), 1e-13);
  EXPECT_GE(w.result.face_crossings, 4);
}

TEST(Trace, ReflectionEndsAtTheMirrorImage) {
  const InputMesh m = testing::make_square_grid(4, true);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
  const Vector3d start(0.5, 0.5, 0.0);
  const double theta = 0.3, length = 1.0;
  const Walk w = walk(m, d, start, planar(theta), length, BoundaryRule::Reflect);
  // Unfolded end point (0.5 + L cos t, 0.5 + L sin t) mirrored about x = 1.
  const Vector3d expected(2.0 - (0.5 + length * std::cos(theta)), 0.5 + length * std::sin(theta), 0.0);
  EXPECT_LT((w.end - expected).norm(), 1e-12);
  EXPECT_LT((w.heading - Vector3d(-std::cos(theta), std::sin(theta), 0.0)).norm(), 1e-12);
  EXPECT_DOUBLE_EQ(w.result.length, length);
  EXPECT_TRUE(w.result.hit_boundary);

  // Several bounces: a long walk folds back into the square like a billiard (x and y fold
  // independently with period 2).
  auto fold = [](double x) {
    x = std::fmod(x, 2.0);
    if (x < 0) x += 2.0;
    return x <= 1.0 ? x : 2.0 - x;
  };
  const double long_length = 7.3, angle = 0.95;
  const Walk w2 = walk(m, d, Vector3d(0.3, 0.6, 0.0), planar(angle), long_length, BoundaryRule::Reflect);
  const Vector3d unfolded = Vector3d(0.3, 0.6, 0.0) + long_length * planar(angle);
  EXPECT_LT((w2.end - Vector3d(fold(unfolded.x()), fold(unfolded.y()), 0.0)).norm(), 1e-10);
  EXPECT_NEAR(w2.result.length, long_length, 1e-12);
}

TEST(Trace, ReflectionIntoACornerReversesTheHeading) {
  const InputMesh m = testing::make_square_grid(4, true);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
  // Along the diagonal edges into the corner (1, 1): both walls reflect, the walk comes straight back.
  const double to_corner = std::sqrt(0.5);
  const Walk w = walk(m, d, Vector3d(0.5, 0.5, 0.0), planar(std::numbers::pi / 4), to_corner + 0.2,
                      BoundaryRule::Reflect);
  EXPECT_LT((w.end - Vector3d(1.0, 1.0, 0.0) + 0.2 * planar(std::numbers::pi / 4)).norm(), 1e-12);
  EXPECT_LT((w.heading + planar(std::numbers::pi / 4)).norm(), 1e-12);
  EXPECT_NEAR(w.result.length, to_corner + 0.2, 1e-12);
}

TEST(Trace, StopEndsOnTheBoundaryAfterTheDistanceToIt) {
  const InputMesh m = testing::make_square_grid(4, true);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
  const double theta = 0.3;
  const Walk w = walk(m, d, Vector3d(0.5, 0.5, 0.0), planar(theta), 1.0, BoundaryRule::Stop);
  const double distance = 0.5 / std::cos(theta);
  EXPECT_NEAR(w.result.length, distance, 1e-13);
  EXPECT_LT((w.end - Vector3d(1.0, 0.5 + distance * std::sin(theta), 0.0)).norm(), 1e-13);
  EXPECT_TRUE(w.result.hit_boundary);
  // Shorter than the distance to the wall: no boundary involved.
  const Walk shorter = walk(m, d, Vector3d(0.5, 0.5, 0.0), planar(theta), 0.9 * distance, BoundaryRule::Stop);
  EXPECT_FALSE(shorter.result.hit_boundary);
  EXPECT_DOUBLE_EQ(shorter.result.length, 0.9 * distance);
  // Starting on the boundary and heading out: stops at once.
  const Walk out = walk(m, d, Vector3d(1.0, 0.3, 0.0), planar(0.2), 0.5, BoundaryRule::Stop);
  EXPECT_EQ(out.result.length, 0.0);
  EXPECT_TRUE(out.result.hit_boundary);
  EXPECT_LT((out.end - Vector3d(1.0, 0.3, 0.0)).norm(), 1e-14);
  // Starting on the boundary and heading out with Reflect: bounces at once, full length walked.
  const Walk bounce = walk(m, d, Vector3d(1.0, 0.3, 0.0), planar(0.2), 0.5, BoundaryRule::Reflect);
  EXPECT_LT((bounce.end - (Vector3d(1.0, 0.3, 0.0) + 0.5 * Vector3d(-std::cos(0.2), std::sin(0.2), 0.0))).norm(), 1e-12);
}

TEST(Trace, StartsOnVerticesAndEdgesAndHeadingsAlongEdges) {
  const InputMesh m = testing::make_square_grid(4, true);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
  // From an interior grid vertex (a corner of six faces) in 24 directions, some exactly along edges.
  const Vector3d vertex(0.5, 0.5, 0.0);
  for (int k = 0; k < 24; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / 24;
    const Walk w = walk(m, d, vertex, planar(angle), 0.3, BoundaryRule::Reflect);
    EXPECT_LT((w.end - (vertex + 0.3 * planar(angle))).norm(), 1e-13) << "direction " << k;
  }
  // Along a grid line (edges of the mesh) through several vertices.
  const Walk along = walk(m, d, Vector3d(0.1, 0.5, 0.0), planar(0.0), 0.8, BoundaryRule::Reflect);
  EXPECT_LT((along.end - Vector3d(0.9, 0.5, 0.0)).norm(), 1e-13);
  EXPECT_FALSE(along.result.hit_boundary);
  // Along the boundary itself, from a boundary corner.
  const Walk wall = walk(m, d, Vector3d(0.0, 0.0, 0.0), planar(0.0), 0.6, BoundaryRule::Stop);
  EXPECT_LT((wall.end - Vector3d(0.6, 0.0, 0.0)).norm(), 1e-13);
  EXPECT_NEAR(wall.result.length, 0.6, 1e-15);
  // From the middle of an interior edge, across it and along it.
  for (double angle : {0.0, std::numbers::pi / 2, std::numbers::pi, 1.0, -2.0}) {
    const Walk w = walk(m, d, Vector3d(0.375, 0.25, 0.0), planar(angle), 0.1, BoundaryRule::Reflect);
    EXPECT_LT((w.end - (Vector3d(0.375, 0.25, 0.0) + 0.1 * planar(angle))).norm(), 1e-13);
  }
}

TEST(Trace, ZeroAndInvalidLengthsReturnTheStart) {
  const InputMesh m = testing::make_square_grid(2, true);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
  const Vector2d p(0.1, 0.05);
  ASSERT_TRUE(inside_face(d, 0, p));
  std::vector<TraceSegment> segments(5);
  for (double length : {0.0, -1.0, std::nan("")}) {
    const TraceResult r = trace(d, 0, p, Vector2d(1.0, 1.0), length, BoundaryRule::Reflect, &segments);
    EXPECT_EQ(r.face, 0);
    EXPECT_EQ(r.position, p);
    EXPECT_EQ(r.length, 0.0);
    EXPECT_LT((r.heading - Vector2d(1.0, 1.0).normalized()).norm(), 1e-15);
    ASSERT_EQ(segments.size(), 1u);
    EXPECT_EQ(segments[0].start, segments[0].end);
  }
  // A zero or NaN heading never produces NaN.
  for (const Vector2d& h : {Vector2d(0.0, 0.0), Vector2d(std::nan(""), 1.0)}) {
    const TraceResult r = trace(d, 0, p, h, 0.7, BoundaryRule::Reflect);
    EXPECT_TRUE(r.position.allFinite());
    EXPECT_TRUE(r.heading.allFinite());
    EXPECT_TRUE(inside_face(d, r.face, r.position));
  }
}

TEST(Trace, ClosedLoopAroundAPrismReturnsToItsStart) {
  const double height = 0.5;
  const InputMesh m = octagonal_band(height);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
  const double perimeter = kSides * kSideLength;
  for (double s0 : {0.1, 0.5 * kSideLength, 3.3}) {
    const Vector3d start = band_point(s0, 0.2);
    const Vector3d tangent = (band_point(s0 + 1e-3, 0.2) - band_point(s0 - 1e-3, 0.2)).normalized();
    const Walk w = walk(m, d, start, tangent, perimeter, BoundaryRule::Reflect);
    EXPECT_LT((w.end - start).norm(), 1e-9);
    EXPECT_LT((w.heading - tangent).norm(), 1e-9);
    EXPECT_GE(w.result.face_crossings, 2 * kSides - 1);
    EXPECT_FALSE(w.result.hit_boundary);
  }
  // A helix that reflects between the rims: unrolled, a billiard in a periodic strip.
  const double slope = 0.4, length = 2.5 * perimeter;
  const Vector3d start = band_point(0.3, 0.1);
  const Vector3d tangent = (band_point(0.3 + 1e-3, 0.1) - band_point(0.3 - 1e-3, 0.1)).normalized();
  const Vector3d heading = std::cos(slope) * tangent + std::sin(slope) * Vector3d(0, 0, 1);
  const Walk w = walk(m, d, start, heading, length, BoundaryRule::Reflect);
  double z = std::fmod(0.1 + length * std::sin(slope), 2.0 * height);
  if (z > height) z = 2.0 * height - z;
  EXPECT_LT((w.end - band_point(0.3 + length * std::cos(slope), z)).norm(), 1e-9);
  EXPECT_TRUE(w.result.hit_boundary);
}

// ---- traces on intrinsic triangulations (flipped and refined) ----------------------------------

// The 3D point of an intrinsic vertex: barycentric interpolation on the input face it sits on.
Vector3d located(const InputMesh& input, const SurfacePoint& p) {
  const auto& t = input.triangles[p.face];
  return p.barycentric[0] * input.positions[t[0]] + p.barycentric[1] * input.positions[t[1]] +
         p.barycentric[2] * input.positions[t[2]];
}

// The affine map from intrinsic face f's 2D frame to 3D through its corners' input locations. Exact
// wherever the face lies in one plane of the input (flat regions), which is where the tests use it.
struct IntrinsicFaceMap {
  std::array<Vector3d, 3> corner;
  const SurfaceDomain* d;
  int f;
  IntrinsicFaceMap(const InputMesh& input, const SurfaceDomain& domain, int face) : d(&domain), f(face) {
    for (int k = 0; k < 3; ++k) corner[k] = located(input, domain.vertex_location[domain.face_vertices[face][k]]);
  }
  Vector3d point(const Vector2d& p) const {
    const Eigen::Vector3d b = barycentric_in_face(*d, f, p);
    return b[0] * corner[0] + b[1] * corner[1] + b[2] * corner[2];
  }
  Vector3d direction(const Vector2d& h) const { return point(h) - point(Vector2d::Zero()); }
  // The 2D direction whose image is the 3D direction h (h in the face's plane).
  Vector2d local_direction(const Vector3d& h) const {
    Eigen::Matrix<double, 3, 2> jacobian;
    jacobian << direction(Vector2d(1.0, 0.0)), direction(Vector2d(0.0, 1.0));
    return (jacobian.transpose() * jacobian).inverse() * (jacobian.transpose() * h);
  }
};

TEST(Trace, StraightWalksOnARefinedIntrinsicSquareAreEuclideanSegments) {
  // shape:square is the unit square; flipped to Delaunay and refined (circumcenters inside, midpoints
  // of boundary edges), its intrinsic faces are still flat triangles of the plane, but with vertices
  // that exist only through their input locations. A trace mapped back through those locations must
  // be the Euclidean segment, folded at the walls like a billiard.
  const InputMesh input = load_mesh("shape:square");
  IntrinsicTriangulation triangulation(input);
  triangulation.flip_to_delaunay();
  RefinementOptions options;
  options.max_circumradius = 0.012;  // the grid's triangles have 0.022
  const RefinementResult refined = triangulation.refine(options);
  ASSERT_GT(refined.circumcenter_insertions, 100u);
  ASSERT_GT(refined.boundary_splits, 0u);
  const SurfaceDomain d = build_surface_domain(triangulation.snapshot());
  ASSERT_EQ(d.vertex_count, input.vertex_count() + static_cast<int>(refined.insertions()));
  for (int v = 0; v < input.vertex_count(); ++v)
    ASSERT_LT((located(input, d.vertex_location[v]) - input.positions[v]).norm(), 1e-15) << "input vertex " << v;

  auto fold = [](double x, double* sign) {
    x = std::fmod(x, 2.0);
    if (x < 0) x += 2.0;
    *sign = x <= 1.0 ? 1.0 : -1.0;
    return x <= 1.0 ? x : 2.0 - x;
  };
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<TraceSegment> segments;
  int crossings = 0, reflected = 0;
  for (int i = 0; i < 200; ++i) {
    const int f = std::min(static_cast<int>(u(rng) * d.face_count), d.face_count - 1);
    double b1 = u(rng), b2 = u(rng);
    if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
    const auto& c = d.face_corners[f];
    const Vector2d start = (1.0 - b1 - b2) * c[0] + b1 * c[1] + b2 * c[2];
    const double angle = 2.0 * std::numbers::pi * u(rng);
    const double length = i < 100 ? 0.3 * u(rng) : 2.5 * u(rng);  // short walks, then long bouncing ones
    const IntrinsicFaceMap start_map(input, d, f);
    const Vector3d start_3d = start_map.point(start);
    const Vector3d heading_3d(std::cos(angle), std::sin(angle), 0.0);
    const TraceResult r =
        trace(d, f, start, start_map.local_direction(heading_3d), length, BoundaryRule::Reflect, &segments);
    ASSERT_TRUE(inside_face(d, r.face, r.position)) << "trace " << i;
    crossings += r.face_crossings;
    reflected += r.hit_boundary ? 1 : 0;

    const Vector3d unfolded = start_3d + length * heading_3d;
    double sx = 1.0, sy = 1.0;
    const Vector3d expected(fold(unfolded.x(), &sx), fold(unfolded.y(), &sy), 0.0);
    const IntrinsicFaceMap end_map(input, d, r.face);
    // Rounding builds up over the frame changes (~10 a unit of length here, 1e-12 .. 1e-13 each).
    EXPECT_LT((end_map.point(r.position) - expected).norm(), 1e-8) << "trace " << i << ", length " << length;
    EXPECT_LT((end_map.direction(r.heading) - Vector3d(sx * heading_3d.x(), sy * heading_3d.y(), 0.0)).norm(), 1e-8)
        << "trace " << i;
    EXPECT_NEAR(r.length, length, 1e-12 * std::max(1.0, length));
  }
  EXPECT_GT(crossings, 2000) << "the walks must cross many intrinsic faces";
  EXPECT_GT(reflected, 20) << "and reflect at refined boundary edges";
}

// A point of the side of the shipped octagonal prism (radius 0.5: corners at angles 2 pi k / 8) at
// arc length s around it from corner 0 and height z, and the horizontal tangent there.
constexpr double kPrismRadius = 0.5;
Vector3d prism_side_point(double s, double z) {
  const Vector3d p = kPrismRadius * band_point(s / kPrismRadius, 0.0);
  return {p.x(), p.y(), z};
}
Vector3d prism_side_tangent(double s) {
  return (prism_side_point(s + 1e-4, 0.0) - prism_side_point(s - 1e-4, 0.0)).normalized();
}

// Unrolled, the prism's side is a flat periodic strip: the horizontal geodesic closes after one
// perimeter, 8 * 2 r sin(pi / 8), arriving where it started with the heading it started with. Checked
// on the shipped shape as loaded, and on its flipped and refined intrinsic triangulation, where the
// loop crosses faces that exist only intrinsically (those straddling the side's folds included).
TEST(Trace, HorizontalLoopAroundTheShippedPrismReturnsToItsStartWithItsHeading) {
  const InputMesh input = load_mesh("shape:octagonal-prism");
  const double perimeter = kSides * 2.0 * kPrismRadius * std::sin(std::numbers::pi / kSides);
  IntrinsicTriangulation triangulation(input);
  triangulation.flip_to_delaunay();
  RefinementOptions options;
  options.max_circumradius = 0.08;
  ASSERT_GT(triangulation.refine(options).insertions(), 0u);
  const SurfaceDomain as_loaded = build_surface_domain(intrinsic_mesh_from_input(input));
  const SurfaceDomain refined = build_surface_domain(triangulation.snapshot());

  for (const SurfaceDomain* d : {&as_loaded, &refined}) {
    SCOPED_TRACE(d == &as_loaded ? "as loaded" : "refined");
    // Edge lengths from the input's coordinates are exact to ~1e-16; those of the refined faces come
    // out of chains of circumcenter insertions and carry ~1e-9 relative rounding (a loop then closes
    // to ~3e-9 m and ~2e-9 rad), far below any real error (a wrong transition is off by O(1)).
    const double tolerance = d == &as_loaded ? 1e-9 : 1e-8;
    int loops = 0;
    // Starts in the middle of three side panels, well away from the folds (panel edges at multiples
    // of 0.383, caps at z = +-0.75) and from the rows and columns of the input grid.
    for (double s0 : {0.18, 1.35, 2.47}) {
      for (double z : {-0.33, 0.1, 0.41}) {
        const Vector3d start_3d = prism_side_point(s0, z);
        // The intrinsic face containing the start whose corners all lie in the start's side panel
        // (one flat rectangle of the side), so the affine map to 3D is exact there.
        const int panel = std::min(static_cast<int>(s0 / (perimeter / kSides)), kSides - 1);
        const Vector3d normal = (octagon_corner(panel, 0.0) + octagon_corner(panel + 1, 0.0)).normalized();
        const double offset = kPrismRadius * octagon_corner(panel, 0.0).dot(normal);
        int face = -1;
        Vector2d start;
        for (int f = 0; f < d->face_count && face < 0; ++f) {
          const IntrinsicFaceMap map(input, *d, f);
          bool in_panel = true;
          for (const Vector3d& c : map.corner) in_panel = in_panel && std::abs(c.dot(normal) - offset) < 1e-12;
          if (!in_panel) continue;
          // The 2D point whose image is the start (least squares; exact when the start is in the plane).
          Eigen::Matrix<double, 3, 2> jacobian;
          jacobian << map.direction(Vector2d(1.0, 0.0)), map.direction(Vector2d(0.0, 1.0));
          const Vector2d p =
              (jacobian.transpose() * jacobian).inverse() * (jacobian.transpose() * (start_3d - map.corner[0]));
          if (inside_face(*d, f, p, -1e-9) && (map.point(p) - start_3d).norm() < 1e-12) face = f, start = p;
        }
        ASSERT_GE(face, 0) << "no face of the panel strictly contains the start at s " << s0 << ", z " << z;
        const Vector2d heading = IntrinsicFaceMap(input, *d, face).local_direction(prism_side_tangent(s0));
        const TraceResult r = trace(*d, face, start, heading, perimeter, BoundaryRule::Reflect);
        EXPECT_EQ(r.face, face) << "s " << s0 << ", z " << z;
        EXPECT_LT((r.position - start).norm(), tolerance) << "s " << s0 << ", z " << z;
        EXPECT_LT((r.heading - heading).norm(), tolerance) << "s " << s0 << ", z " << z;
        EXPECT_GE(r.face_crossings, 2 * kSides - 1);
        EXPECT_FALSE(r.hit_boundary);
        ++loops;
      }
    }
    EXPECT_EQ(loops, 9);
  }
}

TEST(Trace, RandomWalksOnASphereStayValid) {
  const InputMesh m = load_mesh("shape:sphere");
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<TraceSegment> segments;
  for (int i = 0; i < 3000; ++i) {
    const int f = std::min(static_cast<int>(u(rng) * d.face_count), d.face_count - 1);
    // Random barycentric point, sometimes exactly on an edge or a corner.
    double b1 = u(rng), b2 = u(rng);
    if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
    if (i % 5 == 1) b2 = 0.0;
    if (i % 5 == 2) b1 = b2 = 0.0;
    const auto& c = d.face_corners[f];
    const Vector2d start = (1.0 - b1 - b2) * c[0] + b1 * c[1] + b2 * c[2];
    // Random heading, sometimes exactly along an edge of the start face.
    const double angle = 2.0 * std::numbers::pi * u(rng);
    const Vector2d heading = i % 7 == 3 ? Vector2d(1.0, 0.0) : Vector2d(std::cos(angle), std::sin(angle));
    const double length = 8.0 * u(rng);  // up to well over a great circle
    const TraceResult r = trace(d, f, start, heading, length, BoundaryRule::Reflect, &segments);
    ASSERT_TRUE(inside_face(d, r.face, r.position)) << "trace " << i;
    ASSERT_TRUE(r.heading.allFinite());
    EXPECT_NEAR(r.heading.norm(), 1.0, 1e-12);
    EXPECT_NEAR(r.length, length, 1e-12 * std::max(1.0, length));
    EXPECT_FALSE(r.hit_boundary);
    double total = 0.0;
    for (const TraceSegment& s : segments) total += (s.end - s.start).norm();
    EXPECT_NEAR(total, length, 1e-9 * std::max(1.0, length));
  }
}

TEST(Trace, RandomWalksWithBoundariesStayInside) {
  // A square and a single needle-like triangle (10 degree corner): many reflections, some deep in
  // acute corners, where a walk may bounce between two walls several times in a row.
  InputMesh needle;
  needle.source = "test:needle";
  needle.positions = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {std::cos(0.1745), std::sin(0.1745), 0.0}};
  needle.triangles = {{0, 1, 2}};
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<TraceSegment> segments;
  for (const InputMesh& m : {testing::make_square_grid(3, true), needle}) {
    const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(m));
    for (int i = 0; i < 2000; ++i) {
      const int f = std::min(static_cast<int>(u(rng) * d.face_count), d.face_count - 1);
      double b1 = u(rng), b2 = u(rng);
      if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
      if (i % 4 == 1) b1 = b2 = 0.0;  // at a corner
      const auto& c = d.face_corners[f];
      const Vector2d start = (1.0 - b1 - b2) * c[0] + b1 * c[1] + b2 * c[2];
      const double angle = 2.0 * std::numbers::pi * u(rng), length = 5.0 * u(rng);
      const BoundaryRule rule = i % 2 ? BoundaryRule::Reflect : BoundaryRule::Stop;
      const TraceResult r = trace(d, f, start, Vector2d(std::cos(angle), std::sin(angle)), length, rule, &segments);
      ASSERT_TRUE(inside_face(d, r.face, r.position)) << m.source << " trace " << i;
      ASSERT_TRUE(r.heading.allFinite());
      if (rule == BoundaryRule::Reflect) EXPECT_NEAR(r.length, length, 1e-12 * std::max(1.0, length));
      else EXPECT_LE(r.length, length);
      double total = 0.0;
      for (const TraceSegment& s : segments) {
        EXPECT_TRUE(inside_face(d, s.face, s.end, 1e-9));
        total += (s.end - s.start).norm();
      }
      EXPECT_NEAR(total, r.length, 1e-9 * std::max(1.0, length));
    }
  }
}

}  // namespace
}  // namespace physarum
