// Loading the real test meshes of ../shared/meshes (skipped when the folder is absent).
//
// Where the expected counts come from: a separate python3 script (not part of the project, run
// once by hand on the OBJ files) that parses the v/f lines itself, triangulates quads along a
// diagonal that is not already an edge, groups the triangles around each vertex into fans (union
// of triangles sharing an edge at that vertex), gives every fan its own vertex, and then counts
// edges, edge-connected components, boundary loops (chains of halfedges without a twin) and
// genus = sum over components of (2 - chi - b) / 2. Its output:
//   cow      V 2904 F 5804  E 8706   components 1  boundary 0  genus 0  split 1 (file vertex 253, 2 fans)
//   fandisk  V 6475 F 12946 E 19419  components 1  boundary 0  genus 0  split 0
//   spot     V 2930 F 5856  E 8784   components 1  boundary 0  genus 0  (3225 vt lines, all distinct)
//   bunny    V 34834 F 69451 E 104288 components 1 boundary 5  genus 0  (35947 v lines)
//   suzanne  V 507  F 968   E 1473   components 3  boundary 4  genus 0  (468 quads)
//   teapot   V 3691 F 6320  E 9998   components 19 boundary 25 genus 0  split 38 (47 extra fans; 3644 v lines)
#include "common/mesh/mesh_loading.hpp"
#include "mesh_invariants.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>

#include <chrono>
#include <fstream>
#include <sstream>

namespace physarum {
namespace {

struct Expected {
  int vertices, faces, edges, components, boundary_loops, genus, split, dropped, triangulated;
};

void expect_counts(const InputMesh& m, const Expected& e) {
  testing::expect_valid_input_mesh(m);
  const InputMeshStatistics s = compute_statistics(m);
  EXPECT_EQ(s.vertices, e.vertices);
  EXPECT_EQ(s.faces, e.faces);
  EXPECT_EQ(s.edges, e.edges);
  EXPECT_EQ(s.components, e.components);
  EXPECT_EQ(s.boundary_loops, e.boundary_loops);
  EXPECT_EQ(s.genus, e.genus);
  EXPECT_EQ(m.split_vertices, e.split);
  EXPECT_EQ(m.dropped_unreferenced, e.dropped);
  EXPECT_EQ(m.triangulated_polygons, e.triangulated);
}

TEST(MeshLoading, SpotKeepsItsTextureCoordinatesCornerByCorner) {
  PHYSARUM_REQUIRE_SHARED_MESH(path, "spot.obj");
  const InputMesh m = load_mesh(path);
  expect_counts(m, {2930, 5856, 8784, 1, 0, 0, 0, 0, 0});
  EXPECT_TRUE(m.warnings.empty());
  ASSERT_EQ(m.triangle_uvs.size(), m.triangles.size());

  // Parse the file's v, vt and f lines here and compare every corner: spot needs no repair, so
  // triangle t is face t with its corners in file order.
  std::ifstream in(path);
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector2d> vt;
  std::vector<std::array<std::pair<int, int>, 3>> f;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "v") {
      double x, y, z;
      words >> x >> y >> z;
      v.emplace_back(x, y, z);
    } else if (key == "vt") {
      double s, t;
      words >> s >> t;
      vt.emplace_back(s, t);
    } else if (key == "f") {
      std::array<std::pair<int, int>, 3> face;
      for (auto& corner : face) {
        std::string w;
        words >> w;
        corner = {std::stoi(w) - 1, std::stoi(w.substr(w.find('/') + 1)) - 1};
      }
      f.push_back(face);
    }
  }
  ASSERT_EQ(f.size(), m.triangles.size());
  for (size_t t = 0; t < f.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(m.file_vertex[m.triangles[t][c]], f[t][c].first);
      // Coordinates pass through OpenMesh's float parser: equal to single precision.
      EXPECT_LT((m.positions[m.triangles[t][c]] - v[f[t][c].first]).norm(), 1e-6);
      ASSERT_LT((m.uvs[m.triangle_uvs[t][c]] - vt[f[t][c].second]).norm(), 1e-6) << "triangle " << t << " corner " << c;
    }
}

TEST(MeshLoading, CowSplitsItsHourglassVertex) {
  PHYSARUM_REQUIRE_SHARED_MESH(path, "cow.obj");
  const InputMesh m = load_mesh(path);
  expect_counts(m, {2904, 5804, 8706, 1, 0, 0, 1, 0, 0});
  // The one extra vertex is a copy of file vertex 253, at the same place.
  ASSERT_EQ(m.vertex_count(), 2904);
  EXPECT_EQ(m.file_vertex.back(), 253);
  EXPECT_EQ(m.positions.back(), m.positions[253]);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("split 1 non-manifold vertex"), std::string::npos) << m.warnings[0];
  EXPECT_TRUE(m.triangle_uvs.empty());
}

TEST(MeshLoading, TeapotSplitsVerticesSharedByBoundaryLoops) {
  PHYSARUM_REQUIRE_SHARED_MESH(path, "teapot.obj");
  const InputMesh m = load_mesh(path);
  expect_counts(m, {3691, 6320, 9998, 19, 25, 0, 38, 0, 0});
  EXPECT_EQ(m.vertex_count() - 3644, 47) << "one new vertex per extra fan";
  for (int v = 3644; v < m.vertex_count(); ++v) EXPECT_EQ(m.positions[v], m.positions[m.file_vertex[v]]);
}

TEST(MeshLoading, SuzanneQuadsAreTriangulatedWithoutDuplicateDiagonals) {
  PHYSARUM_REQUIRE_SHARED_MESH(path, "suzanne.obj");
  // Faces 142 and 143 of suzanne.obj share three vertices; splitting both along their 0-2
  // diagonal would put four triangles on edge 70-138, so the triangulation must pick the other.
  const InputMesh m = load_mesh(path);
  expect_counts(m, {507, 468 * 2 + 32, 1473, 3, 4, 0, 0, 0, 468});
}

TEST(MeshLoading, FandiskIsAClosedGenusZeroPart) {
  PHYSARUM_REQUIRE_SHARED_MESH(path, "fandisk.obj");
  expect_counts(load_mesh(path), {6475, 12946, 19419, 1, 0, 0, 0, 0, 0});
}

TEST(MeshLoading, BunnyDropsUnreferencedVerticesAndLoadsFast) {
  PHYSARUM_REQUIRE_SHARED_MESH(path, "stanford-bunny.obj");
  const auto t0 = std::chrono::steady_clock::now();
  const InputMesh m = load_mesh(path);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  expect_counts(m, {34834, 69451, 104288, 1, 5, 0, 0, 35947 - 34834, 0});
  // file_vertex is strictly increasing when only unreferenced vertices were dropped.
  for (int v = 1; v < m.vertex_count(); ++v) ASSERT_LT(m.file_vertex[v - 1], m.file_vertex[v]);
#ifdef NDEBUG
  // A guard against quadratic behaviour (minutes), not a speed test: it takes ~0.5 s alone and must
  // pass on a busy 2-core machine; bench/ measures speed.
  EXPECT_LT(seconds, 10.0) << "loading a 2.4 MB OBJ took far too long";
#endif
  RecordProperty("load_seconds", std::to_string(seconds));
}

TEST(MeshLoading, SameMeshThroughOffPlyAndStl) {
  // The reader path for every format: write the same two-triangle square in each and compare.
  testing::TempDir dir;
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir.path / name, std::ios::binary) << text;
    return (dir.path / name).string();
  };
  const std::string obj = write("sq.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const std::string off = write("sq.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  const std::string ply = write("sq.ply",
                                "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                                "property float u\nproperty float v\n"
                                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n");
  const std::string stl = write("sq.stl",
                                "solid sq\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n"
                                "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid sq\n");
  for (const std::string& path : {obj, off, ply, stl}) {
    SCOPED_TRACE(path);
    const InputMesh m = load_mesh(path);
    testing::expect_valid_input_mesh(m);
    const InputMeshStatistics s = compute_statistics(m);
    // STL repeats each corner per facet; identical positions must be merged into 4 vertices.
    EXPECT_EQ(s.vertices, 4);
    EXPECT_EQ(s.faces, 2);
    EXPECT_EQ(s.boundary_loops, 1);
    EXPECT_DOUBLE_EQ(s.area, 1.0);
    for (const auto& t : m.triangles)
      EXPECT_GT((m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).z(), 0);
    EXPECT_EQ(m.triangulated_polygons, path == stl ? 0 : 1);
  }
  // PLY per-vertex texture coordinates (u, v properties) arrive with the mesh.
  const InputMesh m = load_mesh(ply);
  ASSERT_EQ(m.triangle_uvs.size(), 2u);
  for (int t = 0; t < 2; ++t)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& p = m.positions[m.triangles[t][c]];
      EXPECT_EQ(m.uvs[m.triangle_uvs[t][c]], Eigen::Vector2d(p.x(), p.y()));
    }
}

}  // namespace
}  // namespace physarum
