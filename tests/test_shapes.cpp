// Procedural shapes: topology (Euler characteristic, genus, boundary loops) and area against
// analytic values, orientation, and the skinny sphere's defining property (negative cotan
// weights). Every expected value below comes from geometry, not from running the code.
#include "common/base/errors.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/mesh/shapes.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <numbers>
#include <set>

namespace physarum {
namespace {

constexpr double pi = std::numbers::pi;

double triangle_area(const InputMesh& m, const std::array<int, 3>& t) {
  return 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm();
}

// Signed volume enclosed by a closed mesh (divergence theorem); positive iff it is oriented
// outward.
double signed_volume(const InputMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) v += m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]])) / 6.0;
  return v;
}

int euler_characteristic(const InputMeshStatistics& s) { return s.vertices - s.edges + s.faces; }

TEST(Shapes, NamesAreTheDocumentedOnesAndAllLoadClean) {
  const std::set<std::string> expected{"square", "disk", "sphere", "skinny-sphere", "torus", "octagonal-prism", "cube"};
  const auto names = shape_names();
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), expected);
  for (const std::string& name : names) {
    const InputMesh m = load_mesh("shape:" + name);
    EXPECT_EQ(m.source, "shape:" + name);
    EXPECT_TRUE(m.warnings.empty()) << name << ": " << m.warnings.front();
    EXPECT_EQ(m.split_vertices, 0) << name;
    EXPECT_EQ(m.dropped_unreferenced, 0) << name;
    ASSERT_EQ(m.file_vertex.size(), m.positions.size()) << name;
    for (int v = 0; v < m.vertex_count(); ++v) ASSERT_EQ(m.file_vertex[v], v) << name << ": identity map expected";
    EXPECT_LT(m.vertex_count(), 5000) << name << ": shapes stay small";
  }
}

TEST(Shapes, UnknownShapeListsTheValidNames) {
  try {
    load_mesh("shape:dodecahedron");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("shape:dodecahedron"), std::string::npos) << what;
    for (const std::string& name : shape_names()) EXPECT_NE(what.find(name), std::string::npos) << what;
  }
}

TEST(Shapes, SquareIsTheUnitSquareWithOneBoundary) {
  const InputMesh m = load_mesh("shape:square");
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_EQ(s.vertices, 33 * 33);
  EXPECT_EQ(s.faces, 2 * 32 * 32);
  EXPECT_EQ(euler_characteristic(s), 1);  // a disk
  EXPECT_EQ(s.boundary_loops, 1);
  EXPECT_EQ(s.genus, 0);
  EXPECT_NEAR(s.area, 1.0, 1e-12);
  EXPECT_NEAR(s.bounding_box_diagonal, std::sqrt(2.0), 1e-12);
  for (const auto& t : m.triangles) {  // flat, counter-clockwise seen from +z
    const Eigen::Vector3d n = (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
    EXPECT_GT(n.z(), 0);
    for (int v : t) EXPECT_EQ(m.positions[v].z(), 0.0);
  }
}

TEST(Shapes, DiskAreaIsTheInscribedRegular96Gon) {
  const InputMesh m = load_mesh("shape:disk");
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_EQ(euler_characteristic(s), 1);
  EXPECT_EQ(s.boundary_loops, 1);
  EXPECT_EQ(s.genus, 0);
  // The disk is flat and its boundary is a regular n-gon inscribed in the unit circle, so its area
  // is exactly that polygon's: n/2 sin(2 pi / n), n = 6 * 16 rings.
  const int n = 96;
  EXPECT_NEAR(s.area, n / 2.0 * std::sin(2 * pi / n), 1e-12);
  double max_radius = 0;
  for (const auto& p : m.positions) {
    EXPECT_EQ(p.z(), 0.0);
    max_radius = std::max(max_radius, p.norm());
  }
  EXPECT_NEAR(max_radius, 1.0, 1e-12);
  for (const auto& t : m.triangles)
    EXPECT_GT((m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).z(), 0);
}

TEST(Shapes, SphereIsTheLevel4Icosphere) {
  const InputMesh m = load_mesh("shape:sphere");
  const InputMeshStatistics s = compute_statistics(m);
  // Level-k icosphere: V = 10 * 4^k + 2, F = 20 * 4^k.
  EXPECT_EQ(s.vertices, 2562);
  EXPECT_EQ(s.faces, 5120);
  EXPECT_EQ(euler_characteristic(s), 2);
  EXPECT_EQ(s.genus, 0);
  EXPECT_EQ(s.boundary_loops, 0);
  for (const auto& p : m.positions) EXPECT_NEAR(p.norm(), 1.0, 1e-14);
  // An inscribed convex polyhedron has less area than the sphere and more than the sphere of
  // radius equal to its smallest face-plane distance (which it contains).
  double inradius = 1;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).normalized();
    inradius = std::min(inradius, n.dot(m.positions[t[0]]));
  }
  EXPECT_GT(inradius, 0.99);
  EXPECT_LT(s.area, 4 * pi);
  EXPECT_GT(s.area, 4 * pi * inradius * inradius);
  EXPECT_GT(signed_volume(m), 0) << "oriented outward";
  EXPECT_LT(signed_volume(m), 4.0 / 3.0 * pi);
}

// Cotan weight of each interior edge, (cot alpha + cot beta) / 2, keyed by vertex pair.
std::vector<double> cotan_weights(const InputMesh& m) {
  std::map<std::pair<int, int>, double> w;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      const Eigen::Vector3d u = m.positions[a] - m.positions[c], v = m.positions[b] - m.positions[c];
      w[std::minmax(a, b)] += 0.5 * u.dot(v) / u.cross(v).norm();
    }
  std::vector<double> out;
  for (const auto& [e, x] : w) out.push_back(x);
  return out;
}

TEST(Shapes, SkinnySphereHasManyNegativeCotanWeightsUnlikeTheIcosphere) {
  const InputMesh m = load_mesh("shape:skinny-sphere");
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_GE(s.vertices, 1000);
  EXPECT_LE(s.vertices, 3000);
  EXPECT_EQ(euler_characteristic(s), 2);
  EXPECT_EQ(s.genus, 0);
  for (const auto& p : m.positions) EXPECT_NEAR(p.norm(), 1.0, 1e-14);
  EXPECT_NEAR(s.area, 4 * pi, 0.03 * 4 * pi);
  EXPECT_GT(signed_volume(m), 0);

  const std::vector<double> skinny = cotan_weights(m);
  const auto negative = std::count_if(skinny.begin(), skinny.end(), [](double x) { return x < 0; });
  const auto clearly_negative = std::count_if(skinny.begin(), skinny.end(), [](double x) { return x < -0.2; });
  // One long diagonal per sheared quad: 96 * 15 of the 4608 edges.
  EXPECT_GE(negative, 96 * 15);
  EXPECT_GT(clearly_negative, 96 * 5);
  const std::vector<double> ico = cotan_weights(load_mesh("shape:sphere"));
  EXPECT_EQ(std::count_if(ico.begin(), ico.end(), [](double x) { return x < 0; }), 0) << "the icosphere is Delaunay";
  // Long thin triangles: the worst aspect ratio is far beyond the icosphere's.
  double worst_min_angle = pi;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = m.positions[t[(k + 1) % 3]] - m.positions[t[k]], v = m.positions[t[(k + 2) % 3]] - m.positions[t[k]];
      worst_min_angle = std::min(worst_min_angle, std::atan2(u.cross(v).norm(), u.dot(v)));
    }
  EXPECT_LT(worst_min_angle, 10 * pi / 180);
}

TEST(Shapes, TorusHasGenusOneAndThePolyhedralArea) {
  const InputMesh m = load_mesh("shape:torus");
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_EQ(s.vertices, 64 * 24);
  EXPECT_EQ(euler_characteristic(s), 0);
  EXPECT_EQ(s.genus, 1);
  EXPECT_EQ(s.boundary_loops, 0);
  // Each grid quad of a torus of revolution is a planar isosceles trapezoid, so the mesh area is a
  // sum of trapezoids: parallel sides 2 rho_j sin(pi/N) and 2 rho_{j+1} sin(pi/N) (rho = R + r cos v),
  // height sqrt(((rho_{j+1} - rho_j) cos(pi/N))^2 + (z_{j+1} - z_j)^2).
  const double R = 1.0, r = 0.4;
  const int N = 64, M = 24;
  double exact = 0;
  for (int j = 0; j < M; ++j) {
    const double v0 = 2 * pi * j / M, v1 = 2 * pi * (j + 1) / M;
    const double rho0 = R + r * std::cos(v0), rho1 = R + r * std::cos(v1), z0 = r * std::sin(v0), z1 = r * std::sin(v1);
    const double height = std::hypot((rho1 - rho0) * std::cos(pi / N), z1 - z0);
    exact += N * (rho0 + rho1) * std::sin(pi / N) * height;
  }
  EXPECT_NEAR(s.area, exact, 1e-9 * exact);
  EXPECT_NEAR(s.area, 4 * pi * pi * R * r, 0.01 * 4 * pi * pi * R * r);
  EXPECT_NEAR(signed_volume(m), 2 * pi * pi * R * r * r, 0.02 * 2 * pi * pi * R * r * r) << "oriented outward";
}

TEST(Shapes, OctagonalPrismIsClosedWithTheExactArea) {
  const InputMesh m = load_mesh("shape:octagonal-prism");
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_EQ(euler_characteristic(s), 2);
  EXPECT_EQ(s.genus, 0);
  EXPECT_EQ(s.boundary_loops, 0);
  // Regular octagon of circumradius a: side 2a sin(pi/8), area 8 * a^2/2 * sin(pi/4).
  const double a = 0.5, h = 1.5;
  const double side = 2 * a * std::sin(pi / 8), cap = 4 * a * a * std::sin(pi / 4);
  EXPECT_NEAR(s.area, 8 * side * h + 2 * cap, 1e-12);
  EXPECT_NEAR(signed_volume(m), cap * h, 1e-12);
  // Traces around the side must cross many faces: the side is split into rows.
  int side_faces = 0;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
    if (std::abs(n.z()) < 1e-12 * n.norm()) ++side_faces;
  }
  EXPECT_GE(side_faces, 8 * 2 * 4);
  double total = 0;
  for (const auto& t : m.triangles) total += triangle_area(m, t);
  EXPECT_NEAR(total, s.area, 1e-12);
}

TEST(Shapes, CubeIsClosedAndItsUvTilesMapEachSideWithoutOverlap) {
  const InputMesh m = load_mesh("shape:cube");
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_EQ(euler_characteristic(s), 2);
  EXPECT_EQ(s.boundary_loops, 0);
  EXPECT_EQ(m.vertex_count(), 6 * 24 * 24 + 2);  // V - E + F = 2 with F = 2 x 6 x 24^2, E = 3F / 2
  EXPECT_NEAR(s.area, 6.0, 1e-12);
  EXPECT_NEAR(signed_volume(m), 1.0, 1e-12) << "oriented outward";
  ASSERT_EQ(m.triangle_uvs.size(), m.triangles.size());
  // Each side is its tile, a 3 x 2 grid cell less a 4 % margin: every triangle's UV map is the
  // scaling by (1 - 0.08) / 3 along u and (1 - 0.08) / 2 along v, counterclockwise (u x v the outward
  // normal), inside its side's cell.
  const double su = 0.92 / 3.0, sv = 0.92 / 2.0;
  std::set<std::pair<int, int>> cells;
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const auto& t = m.triangles[f];
    const auto& tu = m.triangle_uvs[f];
    Eigen::Matrix<double, 3, 2> edges3;
    Eigen::Matrix2d edges2;
    for (int k = 1; k < 3; ++k) {
      edges3.col(k - 1) = m.positions[t[k]] - m.positions[t[0]];
      edges2.col(k - 1) = m.uvs[tu[k]] - m.uvs[tu[0]];
    }
    ASSERT_GT(edges2.determinant(), 0.0) << "face " << f << ": its UV triangle is turned over";
    const Eigen::Matrix<double, 3, 2> J = edges3 * edges2.inverse();  // surface per UV unit
    EXPECT_NEAR(J.col(0).norm(), 1.0 / su, 1e-9) << f;
    EXPECT_NEAR(J.col(1).norm(), 1.0 / sv, 1e-9) << f;
    EXPECT_NEAR(J.col(0).dot(J.col(1)), 0.0, 1e-9) << f;
    const Eigen::Vector2d centre = (m.uvs[tu[0]] + m.uvs[tu[1]] + m.uvs[tu[2]]) / 3.0;
    const std::pair<int, int> cell{static_cast<int>(centre.x() * 3.0), static_cast<int>(centre.y() * 2.0)};
    cells.insert(cell);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(m.uvs[tu[k]].x() * 3.0 - cell.first, 0.04 - 1e-9);
      EXPECT_LE(m.uvs[tu[k]].x() * 3.0 - cell.first, 0.96 + 1e-9);
      EXPECT_GE(m.uvs[tu[k]].y() * 2.0 - cell.second, 0.04 - 1e-9);
      EXPECT_LE(m.uvs[tu[k]].y() * 2.0 - cell.second, 0.96 + 1e-9);
    }
  }
  EXPECT_EQ(cells.size(), 6u) << "one tile per side";
}

}  // namespace
}  // namespace physarum
