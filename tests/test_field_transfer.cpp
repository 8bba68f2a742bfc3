// Values moving between numberings (common/base/element_data.hpp, common/surface/field_transfer.hpp): the types
// keep numberings apart at compile time, and the one transfer between input and intrinsic vertices
// is exact where it must be: at input vertices, and for linear fields at every intrinsic vertex.
#include "common/base/element_data.hpp"
#include "common/base/errors.hpp"
#include "common/surface/field_transfer.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "pheromone_test_meshes.hpp"

#include <gtest/gtest.h>

#include <random>
#include <type_traits>

namespace physarum {
namespace {

// ---- numberings are types ------------------------------------------------------------------------

static_assert(!std::is_convertible_v<InputVertexData<double>, IntrinsicVertexData<double>>);
static_assert(!std::is_convertible_v<IntrinsicVertexData<double>, InputVertexData<double>>);
static_assert(!std::is_convertible_v<IntrinsicVertexData<double>, DeviceVertexData<double>>);
static_assert(!std::is_convertible_v<DeviceVertexData<double>, IntrinsicVertexData<double>>);
static_assert(!std::is_convertible_v<IntrinsicVertexData<double>, IntrinsicFaceData<double>>);
static_assert(!std::is_convertible_v<std::vector<double>, IntrinsicVertexData<double>>, "a raw array states no numbering");
// The transfers take only the numbering they are for: intrinsic values cannot be "interpolated"
// as if they were input values, nor input values returned as if they were intrinsic.
static_assert(!std::is_invocable_v<decltype(static_cast<IntrinsicVertexData<double> (*)(
                                       const InputMesh&, const IntrinsicVertexData<SurfacePoint>&,
                                       const InputVertexData<double>&)>(&input_to_intrinsic)),
                                   const InputMesh&, const IntrinsicVertexData<SurfacePoint>&,
                                   const IntrinsicVertexData<double>&>);
static_assert(!std::is_invocable_v<decltype(static_cast<InputVertexData<double> (*)(
                                       const InputVertexData<int>&, const IntrinsicVertexData<double>&)>(
                                       &intrinsic_to_input)),
                                   const InputVertexData<int>&, const InputVertexData<double>&>);

double linear(const Eigen::Vector3d& p) { return 1.0 + 2.0 * p.x() - 0.5 * p.y() + 3.0 * p.z(); }

InputVertexData<double> linear_field(const InputMesh& mesh) {
  InputVertexData<double> f(mesh.positions.size());
  for (size_t v = 0; v < f.size(); ++v) f[v] = linear(mesh.positions[v]);
  return f;
}

Eigen::Vector3d position_of(const InputMesh& mesh, const SurfacePoint& p) {
  const auto& t = mesh.triangles[p.face];
  return p.barycentric[0] * mesh.positions[t[0]] + p.barycentric[1] * mesh.positions[t[1]] +
         p.barycentric[2] * mesh.positions[t[2]];
}

// A refined intrinsic triangulation of a flat shape: the intrinsic vertices' input locations are
// where the intrinsic geometry says they are (every intrinsic edge as long as the straight segment
// between its ends' locations: exact on a flat surface, where geodesics are straight), and a linear
// function carried input -> intrinsic is that function at those places to 1e-9, back to the input
// unchanged.
void expect_linear_transfer_exact(const InputMesh& mesh, double max_circumradius) {
  IntrinsicTriangulation triangulation(mesh);
  triangulation.flip_to_delaunay();
  RefinementOptions options;
  options.max_circumradius = max_circumradius;
  triangulation.refine(options);
  const SurfaceDomain domain = build_surface_domain(triangulation.snapshot());
  ASSERT_GT(domain.vertex_count, 2 * mesh.vertex_count()) << "test premise: refinement inserted many vertices";
  for (int f = 0; f < domain.face_count; ++f)
    for (int i = 0; i < 3; ++i) {
      const int a = domain.face_vertices[f][i], b = domain.face_vertices[f][(i + 1) % 3];
      const double intrinsic = (domain.face_corners[f][(i + 1) % 3] - domain.face_corners[f][i]).norm();
      const double extrinsic = (position_of(mesh, domain.vertex_location[a]) - position_of(mesh, domain.vertex_location[b])).norm();
      ASSERT_NEAR(intrinsic, extrinsic, 1e-9) << "face " << f << " edge " << i;
    }
  const InputVertexData<double> f = linear_field(mesh);
  const IntrinsicVertexData<double> on_intrinsic = input_to_intrinsic(mesh, domain.vertex_location, f);
  for (int i = 0; i < domain.vertex_count; ++i)
    ASSERT_NEAR(on_intrinsic[i], linear(position_of(mesh, domain.vertex_location[i])), 1e-9) << "vertex " << i;
  const InputVertexData<double> back = intrinsic_to_input(mesh, domain.vertex_location, on_intrinsic);
  for (int v = 0; v < mesh.vertex_count(); ++v) ASSERT_EQ(back[v], f[v]) << "input vertex " << v;
}

TEST(FieldTransfer, LinearFieldIsExactOnARefinedSquare) { expect_linear_transfer_exact(load_mesh("shape:square"), 0.01); }
TEST(FieldTransfer, LinearFieldIsExactOnARefinedDisk) { expect_linear_transfer_exact(load_mesh("shape:disk"), 0.015); }

// The check can fail: a location moved off its place breaks the edge-length agreement.
TEST(FieldTransfer, MisplacedLocationIsCaught) {
  const InputMesh mesh = load_mesh("shape:square");
  IntrinsicTriangulation triangulation(mesh);
  triangulation.flip_to_delaunay();
  RefinementOptions options;
  options.max_circumradius = 0.01;
  triangulation.refine(options);
  SurfaceDomain domain = build_surface_domain(triangulation.snapshot());
  const int last = domain.vertex_count - 1;
  ASSERT_GE(last, mesh.vertex_count()) << "an inserted vertex";
  SurfacePoint& p = domain.vertex_location[last];
  p.barycentric = Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3) * 0.5 + p.barycentric * 0.5;
  double worst = 0.0;
  for (int f = 0; f < domain.face_count; ++f)
    for (int i = 0; i < 3; ++i) {
      const int a = domain.face_vertices[f][i], b = domain.face_vertices[f][(i + 1) % 3];
      const double intrinsic = (domain.face_corners[f][(i + 1) % 3] - domain.face_corners[f][i]).norm();
      worst = std::max(worst, std::abs(intrinsic - (position_of(mesh, domain.vertex_location[a]) -
                                                    position_of(mesh, domain.vertex_location[b])).norm()));
    }
  EXPECT_GT(worst, 1e-6);
}

// The intrinsic triangulation keeps the input vertices as intrinsic vertices 0..nV-1 (inserted
// vertices follow); the transfer finds exactly that numbering from the vertex locations.
TEST(FieldTransfer, RefinedTriangulationKeepsInputVerticesFirst) {
  const InputMesh mesh = testing::make_icosphere(1);
  IntrinsicTriangulation triangulation(mesh);
  triangulation.flip_to_delaunay();
  RefinementOptions options;
  options.max_circumradius = 0.15;
  triangulation.refine(options);
  const SurfaceDomain domain = build_surface_domain(triangulation.snapshot());
  ASSERT_GT(domain.vertex_count, mesh.vertex_count()) << "test premise: refinement inserted vertices";
  const InputVertexData<int> map = input_vertex_to_intrinsic(mesh, domain.vertex_location);
  for (int v = 0; v < mesh.vertex_count(); ++v) ASSERT_EQ(map[v], v);
  // Values come back unchanged at the input vertices.
  IntrinsicVertexData<double> intrinsic(static_cast<size_t>(domain.vertex_count));
  for (int i = 0; i < domain.vertex_count; ++i) intrinsic[i] = 10.0 * i + 0.5;
  const InputVertexData<double> input = intrinsic_to_input(mesh, domain.vertex_location, intrinsic);
  for (int v = 0; v < mesh.vertex_count(); ++v) EXPECT_EQ(input[v], 10.0 * v + 0.5);
}

// Should a triangulation ever renumber, the transfer still finds each input vertex by location.
TEST(FieldTransfer, FindsInputVerticesByLocationWhenRenumbered) {
  const InputMesh mesh = testing::make_square_grid(3);
  const IntrinsicMesh as_is = intrinsic_mesh_from_input(mesh);
  // Intrinsic vertices: two inserted ones (face interiors) first, then the input vertices reversed.
  IntrinsicVertexData<SurfacePoint> locations;
  locations.values().push_back({0, Eigen::Vector3d(0.2, 0.3, 0.5)});
  locations.values().push_back({4, Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3)});
  for (int v = mesh.vertex_count() - 1; v >= 0; --v) locations.values().push_back(as_is.vertex_location[v]);
  IntrinsicVertexData<double> intrinsic(locations.size());
  for (size_t i = 0; i < intrinsic.size(); ++i) intrinsic[i] = static_cast<double>(i);
  const InputVertexData<double> input = intrinsic_to_input(mesh, locations, intrinsic);
  for (int v = 0; v < mesh.vertex_count(); ++v) EXPECT_EQ(input[v], 2.0 + (mesh.vertex_count() - 1 - v)) << v;

  locations.values().pop_back();  // input vertex 0 now has no intrinsic vertex on it
  intrinsic.values().pop_back();
  EXPECT_THROW(intrinsic_to_input(mesh, locations, intrinsic), InputError);
}

// Input -> intrinsic interpolates linearly: a linear function of position is reproduced exactly at
// every intrinsic vertex, inserted ones included.
TEST(FieldTransfer, InputToIntrinsicReproducesLinearFields) {
  const InputMesh mesh = testing::make_square_grid(4);
  IntrinsicVertexData<SurfacePoint> locations(intrinsic_mesh_from_input(mesh).vertex_location);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int k = 0; k < 20; ++k) {
    double a = uniform(rng), b = uniform(rng) * (1 - a);
    locations.values().push_back({k % mesh.triangle_count(), Eigen::Vector3d(a, b, 1 - a - b)});
  }
  const InputVertexData<double> field = linear_field(mesh);
  const IntrinsicVertexData<double> sampled = input_to_intrinsic(mesh, locations, field);
  for (size_t i = 0; i < locations.size(); ++i) {
    const auto& t = mesh.triangles[locations[i].face];
    const Eigen::Vector3d p = locations[i].barycentric[0] * mesh.positions[t[0]] +
                              locations[i].barycentric[1] * mesh.positions[t[1]] +
                              locations[i].barycentric[2] * mesh.positions[t[2]];
    EXPECT_NEAR(sampled[i], 1.0 + 2.0 * p.x() - 0.5 * p.y() + 3.0 * p.z(), 1e-12);
  }
  EXPECT_THROW(input_to_intrinsic(mesh, locations, InputVertexData<double>{1.0, 2.0}), InputError);
}

}  // namespace
}  // namespace physarum
