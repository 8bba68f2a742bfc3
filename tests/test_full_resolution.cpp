// The full-resolution result (fields_full.ply): one vertex per intrinsic vertex, placed ON the input
// surface, intrinsic connectivity, values exactly the intrinsic values (parsed back from the file by
// an independent reader); on a flat surface the full mesh re-tiles the input exactly, so a linear
// function of position is reproduced everywhere. The multi-field PLY writer keeps pheromone.ply's
// layout byte for byte, refuses bad field lists, and the previewer draws degenerate faces safely.
#include "common/base/errors.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/output/ply_writer.hpp"
#include "common/output/preview_image.hpp"
#include "common/setup/scene_surface.hpp"
#include "pheromone_test_meshes.hpp"
#include "ply_layout_parser.hpp"
#include "test_support.hpp"
#include "uv_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cfloat>
#include <fstream>
#include <iterator>
#include <random>

namespace physarum {
namespace {

using testing::TempDir;

// Distance from p to triangle a b c (brute force over the face, its edges and its corners).
double distance_to_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  double best = HUGE_VAL;
  if (n.norm() > 0) {
    const Eigen::Vector3d unit = n.normalized();
    const Eigen::Vector3d q = p - unit * (p - a).dot(unit);
    // Inside when q is on the inner side of all three edges.
    if ((b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 && (a - c).cross(q - c).dot(n) >= 0)
      best = std::abs((p - a).dot(unit));
  }
  for (const auto& [s, t] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
    const double along = std::clamp((p - s).dot(t - s) / std::max((t - s).squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (p - (s + along * (t - s))).norm());
  }
  return best;
}

double distance_to_mesh(const Eigen::Vector3d& p, const InputMesh& mesh) {
  double best = HUGE_VAL;
  for (const auto& t : mesh.triangles)
    best = std::min(best, distance_to_triangle(p, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]));
  return best;
}

// An icosphere refined intrinsically: inserted vertices lie inside input faces, and Delaunay flips
// make intrinsic edges cross input edges.
PreparedSurface refined_sphere() {
  SurfaceSpec spec;
  spec.mesh = "inline icosphere";
  spec.max_circumradius = 0.12;
  return prepare_surface(testing::make_icosphere(1), spec);
}

TEST(FullResolutionMesh, VerticesAreTheIntrinsicVerticesOnTheInputSurface) {
  const PreparedSurface surface = refined_sphere();
  const SurfaceDomain& domain = surface.domain;
  ASSERT_GT(domain.vertex_count, 3 * surface.input.vertex_count()) << "the refinement should insert many vertices";
  const FullResolutionMesh full = build_full_resolution_mesh(surface.input, domain);
  ASSERT_EQ(full.mesh.vertex_count(), domain.vertex_count);
  ASSERT_EQ(full.mesh.triangles, domain.face_vertices);
  // Input vertices keep their exact positions (intrinsic vertices 0..n-1 are the input vertices).
  for (int v = 0; v < surface.input.vertex_count(); ++v) ASSERT_EQ(full.mesh.positions[v], surface.input.positions[v]) << v;
  // Every vertex lies on the input surface (brute-force distance to all input triangles), and the
  // inserted ones are not all on input edges or corners: most lie strictly inside the unit sphere's
  // chords, i.e. at radius < 1.
  int strictly_inside = 0;
  for (int v = 0; v < full.mesh.vertex_count(); ++v) {
    ASSERT_LT(distance_to_mesh(full.mesh.positions[v], surface.input), 1e-12) << "vertex " << v;
    strictly_inside += full.mesh.positions[v].norm() < 1.0 - 1e-6;
  }
  EXPECT_GT(strictly_inside, domain.vertex_count / 2);
}

// A scaled simulation (scale_to_area) still exports in the input's own coordinates.
TEST(FullResolutionMesh, PositionsAreInTheInputsCoordinatesWhenTheSimulationIsScaled) {
  SurfaceSpec spec;
  spec.mesh = "inline uv rectangle";
  spec.scale_to_area = 48.0;  // 16 x the rectangle's area 3: lengths x 4
  spec.max_circumradius = 0.4;
  const PreparedSurface surface = prepare_surface(testing::make_uv_rectangle(), spec);
  const FullResolutionMesh full = build_full_resolution_mesh(surface.input, surface.domain);
  for (const Eigen::Vector3d& p : full.mesh.positions) {
    ASSERT_GE(p.x(), -1e-12);
    ASSERT_LE(p.x(), 3.0 + 1e-12);
    ASSERT_GE(p.y(), -1e-12);
    ASSERT_LE(p.y(), 1.0 + 1e-12);
    ASSERT_EQ(p.z(), 0.0);
  }
}

// On a flat surface the intrinsic triangulation's geodesics are straight, so the full mesh tiles the
// input exactly: same total area, every face the same way up (no fold or overlap). A field linear in
// position then interpolates to the function at every point of every face.
TEST(FullResolutionMesh, LinearFieldIsExactEverywhereOnAFlatSurface) {
  SurfaceSpec spec;
  spec.mesh = "inline uv rectangle";
  spec.max_circumradius = 0.15;
  const PreparedSurface surface = prepare_surface(testing::make_uv_rectangle(), spec);
  const FullResolutionMesh full = build_full_resolution_mesh(surface.input, surface.domain);
  ASSERT_GT(full.mesh.triangle_count(), 2 * surface.input.triangle_count());
  double area = 0.0;
  for (const auto& t : full.mesh.triangles) {
    const Eigen::Vector3d n = (full.mesh.positions[t[1]] - full.mesh.positions[t[0]])
                                  .cross(full.mesh.positions[t[2]] - full.mesh.positions[t[0]]);
    ASSERT_GT(n.z(), 0.0) << "a face of the full mesh is flipped or degenerate";
    area += 0.5 * n.z();
  }
  EXPECT_NEAR(area, 3.0, 1e-12);

  auto f = [](const Eigen::Vector3d& p) { return 1.0 + 2.0 * p.x() - 0.5 * p.y() + 3.0 * p.z(); };
  IntrinsicVertexData<double> field(static_cast<size_t>(surface.domain.vertex_count));
  for (size_t v = 0; v < field.size(); ++v) field[v] = f(full.mesh.positions[v]);
  const InputVertexData<double> values = full.vertex_values(field);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const auto& t : full.mesh.triangles)
    for (int sample = 0; sample < 4; ++sample) {
      double b1 = unit(rng), b2 = unit(rng);
      if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
      const double b0 = 1.0 - b1 - b2;
      const Eigen::Vector3d p = b0 * full.mesh.positions[t[0]] + b1 * full.mesh.positions[t[1]] + b2 * full.mesh.positions[t[2]];
      ASSERT_NEAR(b0 * values[t[0]] + b1 * values[t[1]] + b2 * values[t[2]], f(p), 1e-12);
    }
}

TEST(FullResolutionMesh, FieldsFullPlyHoldsEveryIntrinsicValueExactly) {
  const PreparedSurface surface = refined_sphere();
  const FullResolutionMesh full = build_full_resolution_mesh(surface.input, surface.domain);
  const int n = surface.domain.vertex_count;
  IntrinsicVertexData<double> pheromone(static_cast<size_t>(n)), second(static_cast<size_t>(n));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(0.0, 5.0);
  for (int v = 0; v < n; ++v) pheromone[v] = value(rng), second[v] = -value(rng);
  const InputVertexData<double> p = full.vertex_values(pheromone), s = full.vertex_values(second);
  TempDir dir;
  const std::string path = (dir.path / "fields_full.ply").string();
  FieldColoring coloring;
  coloring.high = 5.0;
  write_fields_ply(path, full.mesh, {PlyField{"pheromone", p}, PlyField{"species_1", s}}, coloring, "fields per vertex");

  const testing::ParsedPly ply = testing::parse_ply(path);
  ASSERT_EQ(ply.vertices, n);
  ASSERT_EQ(ply.faces, surface.domain.face_count);
  EXPECT_EQ(ply.float_properties, (std::vector<std::string>{"x", "y", "z", "pheromone", "species_1"}));
  const std::vector<float> read_pheromone = ply.property("pheromone"), read_second = ply.property("species_1");
  for (int v = 0; v < n; ++v) {
    ASSERT_EQ(read_pheromone[v], static_cast<float>(pheromone[v])) << v;
    ASSERT_EQ(read_second[v], static_cast<float>(second[v])) << v;
    for (int c = 0; c < 3; ++c) ASSERT_EQ(ply.vertex[v][c], static_cast<float>(full.mesh.positions[v][c]));
    // Colours follow the FIRST field, over 0 .. high.
    ASSERT_EQ(ply.color[v], color_map_color(ColorMap::viridis(), pheromone[v] / 5.0)) << v;
  }
  for (int f = 0; f < ply.faces; ++f) ASSERT_EQ(ply.face[f], surface.domain.face_vertices[f]);
}

// pheromone.ply's layout is a contract: the header, byte for byte, as it was before fields_full.ply.
TEST(FullResolutionMesh, PheromonePlyHeaderIsUnchanged) {
  const InputMesh mesh = testing::make_square_grid(2);
  const InputVertexData<double> values(static_cast<size_t>(mesh.vertex_count()), 0.5);
  TempDir dir;
  const std::string path = (dir.path / "pheromone.ply").string();
  write_field_ply(path, mesh, values);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string expected_header =
      "ply\nformat binary_little_endian 1.0\ncomment physarum: pheromone per input vertex\nelement vertex 9\n"
      "property float x\nproperty float y\nproperty float z\nproperty float pheromone\nproperty uchar red\n"
      "property uchar green\nproperty uchar blue\nelement face 8\nproperty list uchar int vertex_indices\nend_header\n";
  ASSERT_EQ(bytes.substr(0, expected_header.size()), expected_header);
  EXPECT_EQ(bytes.size(), expected_header.size() + 9 * 19 + 8 * 13);
}

TEST(FullResolutionMesh, BadFieldListsAreRefusedAndWriteNothing) {
  const InputMesh mesh = testing::make_square_grid(2);
  const InputVertexData<double> good(static_cast<size_t>(mesh.vertex_count()), 1.0), short_field{1.0, 2.0};
  TempDir dir;
  const std::string path = (dir.path / "fields_full.ply").string();
  const FieldColoring coloring;
  EXPECT_THROW(write_fields_ply(path, mesh, {}, coloring, "x"), InputError);
  EXPECT_THROW(write_fields_ply(path, mesh, {PlyField{"a", good}, PlyField{"a", good}}, coloring, "x"), InputError);
  EXPECT_THROW(write_fields_ply(path, mesh, {PlyField{"two words", good}}, coloring, "x"), InputError);
  EXPECT_THROW(write_fields_ply(path, mesh, {PlyField{"red", good}}, coloring, "x"), InputError);
  EXPECT_THROW(write_fields_ply(path, mesh, {PlyField{"a", good}, PlyField{"b", short_field}}, coloring, "x"), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path));
  FullResolutionMesh full;
  full.mesh = mesh;
  EXPECT_THROW(full.vertex_values(IntrinsicVertexData<double>{1.0}), InputError);
}

// An intrinsic triangulation may have a face whose chords coincide (a loop edge repeats a vertex)
// or are collinear: it is written as it is, and the previewer draws around it without NaNs.
TEST(FullResolutionMesh, DegenerateChordFacesAreWrittenAndPreviewedSafely) {
  InputMesh mesh;
  mesh.source = "degenerate faces";
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 0, 1}, {0, 1, 3}};  // a good face, a repeated vertex, collinear corners
  const InputVertexData<double> values{0.0, 1.0, 2.0, 3.0};
  TempDir dir;
  const std::string path = (dir.path / "fields_full.ply").string();
  write_fields_ply(path, mesh, {PlyField{"pheromone", values}}, FieldColoring{}, "test");
  EXPECT_EQ(testing::parse_ply(path).face, mesh.triangles);
  PreviewOptions options;
  options.width = 64;
  options.height = 48;
  options.azimuth_deg = 0.0;
  options.elevation_deg = 0.0;  // looking at the z = 0 plane from +z
  const RgbImage image = render_preview(mesh, values, options);
  int drawn = 0;
  for (size_t p = 0; p < image.pixels.size(); p += 3)
    drawn += !(image.pixels[p] == 255 && image.pixels[p + 1] == 255 && image.pixels[p + 2] == 255);
  EXPECT_GT(drawn, 100) << "the good face is drawn";
}

}  // namespace
}  // namespace physarum
