// Repair of polygon soups (mesh_repair.hpp) and the statistics of InputMesh, on small hand-made
// inputs whose answers are known by construction.
#include "common/base/errors.hpp"
#include "common/mesh/mesh_polygon_triangulation.hpp"
#include "common/mesh/mesh_repair.hpp"
#include "mesh_invariants.hpp"

#include <Eigen/Geometry>

namespace physarum {
namespace {

PolygonSoup soup(std::vector<Eigen::Vector3d> positions, const std::vector<std::vector<int>>& polygons) {
  PolygonSoup s;
  s.positions = std::move(positions);
  for (const auto& p : polygons) s.add_polygon(p);
  return s;
}

double signed_area_z(const InputMesh& m, const std::array<int, 3>& t) {
  return 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).z();
}

bool contains(const std::vector<std::string>& warnings, const std::string& text) {
  for (const auto& w : warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

TEST(MeshRepair, BowtieVertexIsSplitIntoTwoFans) {
  // Two triangles touching only at vertex 0: one vertex on two boundary loops.
  const InputMesh m = repair_polygon_soup(soup({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}), "bowtie");
  testing::expect_valid_input_mesh(m);
  EXPECT_EQ(m.split_vertices, 1);
  EXPECT_EQ(m.vertex_count(), 6);
  EXPECT_EQ(m.file_vertex[5], 0);
  EXPECT_EQ(m.positions[5], Eigen::Vector3d(0, 0, 0));
  EXPECT_TRUE(contains(m.warnings, "split 1 non-manifold vertex into separate fans")) << m.warnings.size();
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_EQ(s.components, 2);
  EXPECT_EQ(s.boundary_loops, 2);
  EXPECT_EQ(s.genus, 0);
}

TEST(MeshRepair, TwoTetrahedraSharingAVertexBecomeTwoSpheres) {
  // Tetrahedra {0,1,2,3} and {0,4,5,6} (outward orientation) meet at vertex 0 only.
  const std::vector<Eigen::Vector3d> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  const InputMesh m = repair_polygon_soup(
      soup(p, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 5, 4}, {0, 4, 6}, {0, 6, 5}, {4, 5, 6}}), "two tetrahedra");
  testing::expect_valid_input_mesh(m);
  EXPECT_EQ(m.split_vertices, 1);
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_EQ(s.vertices, 8);
  EXPECT_EQ(s.edges, 12);
  EXPECT_EQ(s.faces, 8);
  EXPECT_EQ(s.components, 2);
  EXPECT_EQ(s.boundary_loops, 0);
  EXPECT_EQ(s.genus, 0);
  EXPECT_NEAR(s.area, 2 * (1.5 + std::sqrt(3.0) / 2), 1e-12);
  EXPECT_NEAR(s.bounding_box_diagonal, std::sqrt(12.0), 1e-12);
}

TEST(MeshRepair, InconsistentOrientationIsFixedTowardsTheMajority) {
  // A fan of four triangles around vertex 0 in the plane z = 0; the third is listed clockwise.
  const std::vector<Eigen::Vector3d> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  PolygonSoup s = soup(p, {{0, 1, 2}, {0, 2, 3}, {0, 4, 3}, {0, 4, 1}});
  s.uvs = {{0, 0}, {1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  s.corner_uv = s.corner_vertex;
  const InputMesh m = repair_polygon_soup(s, "fan");
  testing::expect_valid_input_mesh(m);
  for (const auto& t : m.triangles) EXPECT_GT(signed_area_z(m, t), 0) << "majority is counter-clockwise from +z";
  EXPECT_TRUE(contains(m.warnings, "re-oriented 1 face"));
  // Texture coordinates follow their corners through the flip.
  for (int t = 0; t < m.triangle_count(); ++t)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(m.uvs[m.triangle_uvs[t][c]], m.positions[m.triangles[t][c]].head<2>());

  // Same fan with three of four clockwise, the counter-clockwise one listed first (so the
  // propagation starts from the minority): it is the one flipped.
  const InputMesh minority = repair_polygon_soup(soup(p, {{0, 1, 2}, {0, 3, 2}, {0, 4, 3}, {0, 1, 4}}), "fan");
  testing::expect_valid_input_mesh(minority);
  for (const auto& t : minority.triangles) EXPECT_LT(signed_area_z(minority, t), 0);
  EXPECT_TRUE(contains(minority.warnings, "re-oriented 1 face"));
}

TEST(MeshRepair, NonConvexPolygonIsEarClippedWithoutFolds) {
  // An L-shaped hexagon of area 3; a fan from corner 0 would leave the polygon.
  const std::vector<Eigen::Vector3d> p{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  for (int rotate = 0; rotate < 6; ++rotate) {
    std::vector<int> polygon;
    for (int k = 0; k < 6; ++k) polygon.push_back((k + rotate) % 6);
    const InputMesh m = repair_polygon_soup(soup(p, {polygon}), "L");
    testing::expect_valid_input_mesh(m);
    EXPECT_EQ(m.triangle_count(), 4);
    EXPECT_EQ(m.triangulated_polygons, 1);
    double area = 0;
    for (const auto& t : m.triangles) {
      EXPECT_GT(signed_area_z(m, t), 0) << "rotation " << rotate;
      area += signed_area_z(m, t);
    }
    EXPECT_NEAR(area, 3.0, 1e-12);
    EXPECT_NEAR(compute_statistics(m).area, 3.0, 1e-12) << "no overlapping triangles";
  }
}

TEST(MeshRepair, QuadsSharingThreeVerticesAvoidADuplicateDiagonal) {
  // Quads (0,1,2,3) and (0,3,2,4) share edges 0-3 and 2-3 and have the same 0-2 diagonal (the
  // situation of faces 142/143 in suzanne.obj). Cutting both along 0-2 gives four triangles on
  // that edge; the triangulation must take 1-3 and 3-4 instead.
  const std::vector<Eigen::Vector3d> p{{0, 0, 0}, {1, -1, 0.2}, {2, 0, 0}, {1, 0.1, 0.5}, {1, 1, 0.2}};
  const InputMesh m = repair_polygon_soup(soup(p, {{0, 1, 2, 3}, {0, 3, 2, 4}}), "quads");
  testing::expect_valid_input_mesh(m);
  EXPECT_EQ(m.triangle_count(), 4);

  std::unordered_set<std::uint64_t> edges{undirected_edge_key(0, 2)};
  const std::vector<int> quad{0, 1, 2, 3};
  const auto triangles = triangulate_polygon(quad, p, edges);
  ASSERT_EQ(triangles.size(), 2u);
  for (const auto& t : triangles) EXPECT_TRUE(t[0] == 1 || t[1] == 1 || t[2] == 1) << "both triangles use the 1-3 diagonal";
  EXPECT_TRUE(edges.contains(undirected_edge_key(1, 3)));
}

TEST(MeshRepair, DropsShortAndRepeatedFacesAndUnusedVertices) {
  const std::vector<Eigen::Vector3d> p{{9, 9, 9}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {5, 5, 5}};
  const InputMesh m = repair_polygon_soup(soup(p, {{1, 2}, {1, 2, 3}, {2, 4, 2}, {2, 4, 3}}), "messy");
  testing::expect_valid_input_mesh(m);
  EXPECT_EQ(m.triangle_count(), 2);
  EXPECT_EQ(m.dropped_unreferenced, 2);
  EXPECT_EQ(m.file_vertex, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_TRUE(contains(m.warnings, "dropped 1 face with fewer than three corners (the first is face 0)"));
  EXPECT_TRUE(contains(m.warnings, "dropped 1 face with a repeated vertex index (the first is face 2, which uses vertex 2 twice)"));
  EXPECT_TRUE(contains(m.warnings, "dropped 2 vertices used by no face"));
}

TEST(MeshRepair, StatisticsOfAnOpenCylinderAndATorusGrid) {
  // Open cylinder: 8 x 3 quads around the z axis; chi = 0 with two boundary loops, genus 0.
  std::vector<Eigen::Vector3d> p;
  std::vector<std::vector<int>> quads;
  for (int r = 0; r <= 3; ++r)
    for (int k = 0; k < 8; ++k) p.emplace_back(std::cos(k * M_PI / 4), std::sin(k * M_PI / 4), r);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 8; ++k) quads.push_back({8 * r + k, 8 * r + (k + 1) % 8, 8 * (r + 1) + (k + 1) % 8, 8 * (r + 1) + k});
  const InputMesh cylinder = repair_polygon_soup(soup(p, quads), "cylinder");
  testing::expect_valid_input_mesh(cylinder);
  InputMeshStatistics s = compute_statistics(cylinder);
  EXPECT_EQ(s.vertices, 32);
  EXPECT_EQ(s.faces, 48);
  EXPECT_EQ(s.edges, 32 + 48);  // V - E + F = 0
  EXPECT_EQ(s.boundary_loops, 2);
  EXPECT_EQ(s.genus, 0);
  EXPECT_EQ(cylinder.triangulated_polygons, 24);
  // Each planar quad is a 1 x (2 sin(pi/8)) rectangle.
  EXPECT_NEAR(s.area, 24 * 2 * std::sin(M_PI / 8), 1e-12);

  // Closing the cylinder into a torus grid (identify the last ring with the first) gives genus 1.
  std::vector<std::vector<int>> torus_quads;
  std::vector<Eigen::Vector3d> q;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 5; ++j) {
      const double u = 2 * M_PI * i / 6, v = 2 * M_PI * j / 5;
      q.emplace_back((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v));
    }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 5; ++j)
      torus_quads.push_back({i * 5 + j, ((i + 1) % 6) * 5 + j, ((i + 1) % 6) * 5 + (j + 1) % 5, i * 5 + (j + 1) % 5});
  const InputMesh torus = repair_polygon_soup(soup(q, torus_quads), "torus");
  testing::expect_valid_input_mesh(torus);
  s = compute_statistics(torus);
  EXPECT_EQ(s.vertices - s.edges + s.faces, 0);
  EXPECT_EQ(s.genus, 1);
  EXPECT_EQ(s.boundary_loops, 0);
  EXPECT_EQ(s.components, 1);
}

}  // namespace
}  // namespace physarum
