// FE operators: per-face gradients, the Dirichlet-energy identity of the cotan Laplacian (also on
// intrinsic meshes with self-loops and parallel edges), cotan edge weights, and the Fig. 4 effect:
// extrinsic skinny triangles break the discrete maximum principle, intrinsic Delaunay flips restore it.
#include "common/base/errors.hpp"
#include "common/surface/fe_operators.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/surface/surface_domain.hpp"
#include "pheromone_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <random>

namespace physarum {
namespace {

// sum over faces of area * |grad u|^2, the Dirichlet energy (times two) computed from face layouts.
double dirichlet_energy(const SurfaceDomain& d, const std::vector<double>& u) {
  double e = 0.0;
  const std::vector<Eigen::Vector2d> g = face_gradients(d, u);
  for (int f = 0; f < d.face_count; ++f) e += d.face_area[f] * g[f].squaredNorm();
  return e;
}

double quadratic_form(const SurfaceDomain& d, const std::vector<double>& u) {
  std::vector<double> lu;
  d.laplacian.multiply(u, lu);
  double e = 0.0;
  for (size_t i = 0; i < u.size(); ++i) e += u[i] * lu[i];
  return e;
}

TEST(FeOperators, GradientOfALinearFunctionIsExact) {
  const InputMesh input = testing::make_square_grid(5, false, 0.4, 11);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(input));
  std::vector<double> u(d.vertex_count);
  for (int v = 0; v < d.vertex_count; ++v) u[v] = 2.0 * input.positions[v].x() - 3.0 * input.positions[v].y() + 1.0;
  const std::vector<Eigen::Vector2d> g = face_gradients(d, u);
  for (int f = 0; f < d.face_count; ++f) {
    // Face frames are rotated copies of the plane: the gradient keeps its length sqrt(13) ...
    EXPECT_NEAR(g[f].norm(), std::sqrt(13.0), 1e-12);
    // ... and its component along every edge is the difference of the end values.
    for (int i = 0; i < 3; ++i) {
      const auto& c = d.face_corners[f];
      const int a = d.face_vertices[f][i], b = d.face_vertices[f][(i + 1) % 3];
      EXPECT_NEAR(g[f].dot(c[(i + 1) % 3] - c[i]), u[b] - u[a], 1e-12);
    }
  }
}

TEST(FeOperators, LaplacianQuadraticFormIsTheDirichletEnergy) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(testing::make_square_grid(6, false, 0.45, 2)));
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> u(d.vertex_count);
    for (double& x : u) x = normal(rng);
    const double e = dirichlet_energy(d, u);
    EXPECT_NEAR(quadratic_form(d, u), e, 1e-11 * e);
  }
}

TEST(FeOperators, SelfLoopsAndParallelEdgesAccumulateCorrectly) {
  // An intrinsic mesh a simple-graph assembly gets wrong: face 0 has a self-loop at vertex 0
  // (corners 0, 0, 1), faces 1 and 2 both join vertices 0 and 1 through different edges.
  IntrinsicMesh mesh;
  mesh.vertex_count = 3;
  mesh.faces = {{0, 0, 1}, {0, 1, 2}, {1, 0, 2}};
  mesh.edge_lengths = {{1.0, 0.8, 0.7}, {0.8, 0.9, 0.6}, {1.1, 0.75, 0.95}};
  mesh.twin = {{-1, -1, -1}, {-1, -1, -1}, {-1, -1, -1}};
  mesh.vertex_location.resize(3);
  const SurfaceDomain d = build_surface_domain(mesh);
  std::vector<double> ones(3, 1.0), y;
  d.laplacian.multiply(ones, y);
  for (double v : y) EXPECT_NEAR(v, 0.0, 1e-14);
  std::mt19937 rng(9);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> u = {normal(rng), normal(rng), normal(rng)};
    const double e = dirichlet_energy(d, u);
    EXPECT_NEAR(quadratic_form(d, u), e, 1e-12 * std::max(e, 1.0));
  }
  // Lumped mass: vertex 0 is two corners of the self-loop face and one of each other face.
  double mass = 0.0;
  for (double m : d.vertex_mass) mass += m;
  EXPECT_NEAR(mass, d.total_area, 1e-15);
  EXPECT_NEAR(d.vertex_mass[0], (2.0 * d.face_area[0] + d.face_area[1] + d.face_area[2]) / 3.0, 1e-15);
}

TEST(FeOperators, CotanWeightsOfKnownTriangles) {
  // Equilateral triangle, all boundary: each edge weight is cot(60 deg) / 2.
  IntrinsicMesh tri;
  tri.vertex_count = 3;
  tri.faces = {{0, 1, 2}};
  tri.edge_lengths = {{2.0, 2.0, 2.0}};
  tri.twin = {{-1, -1, -1}};
  const auto equilateral = cotan_edge_weights(tri);
  for (double w : equilateral[0]) EXPECT_NEAR(w, 0.5 / std::sqrt(3.0), 1e-15);
  // Right triangle 3-4-5: the hypotenuse (halfedge 1, lengths 3, 5, 4 -> edge 1 has length 5) faces
  // the right angle, weight 0; the leg of length 3 faces the angle with cot = 4/3.
  tri.edge_lengths = {{3.0, 5.0, 4.0}};
  const auto w = cotan_edge_weights(tri)[0];
  EXPECT_NEAR(w[1], 0.0, 1e-15);
  EXPECT_NEAR(w[0], 0.5 * 4.0 / 3.0, 1e-15);
  EXPECT_NEAR(w[2], 0.5 * 3.0 / 4.0, 1e-15);
  EXPECT_NEAR(triangle_area_from_lengths({3.0, 5.0, 4.0}), 6.0, 1e-15);
  // Kahan's formula keeps a needle's area accurate where textbook Heron loses every digit.
  EXPECT_NEAR(triangle_area_from_lengths({1.0, 1.0, 1e-9}) / (0.5e-9), 1.0, 1e-12);
}

// Minimum over vertices of the backward-Euler diffusion of a unit-mass spike at `spike`:
// (M + dt L) u' = M u with u = e_spike / m_spike.
double min_after_backward_euler(const SurfaceDomain& d, int spike, double dt) {
  Eigen::SparseMatrix<double> a(d.laplacian.to_eigen());
  a *= dt;
  for (int v = 0; v < d.vertex_count; ++v) a.coeffRef(v, v) += d.vertex_mass[v];
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(d.vertex_count);
  rhs[spike] = 1.0;  // M u with u = e_spike / m_spike
  const Eigen::VectorXd u = solver.solve(rhs);
  return u.minCoeff() / u.maxCoeff();
}

TEST(FeOperators, IntrinsicFlipsRestoreTheMaximumPrincipleOnTheSkinnySphere) {
  const InputMesh input = load_mesh("shape:skinny-sphere");
  const IntrinsicMesh extrinsic = intrinsic_mesh_from_input(input);

  // The extrinsic mesh has negative cotan weights; remember the worst edge's endpoint for the spike.
  const auto ext_weights = cotan_edge_weights(extrinsic);
  double worst = 0.0, largest = 0.0;
  int spike = -1;
  for (int f = 0; f < extrinsic.face_count(); ++f)
    for (int i = 0; i < 3; ++i) {
      largest = std::max(largest, std::abs(ext_weights[f][i]));
      if (ext_weights[f][i] < worst) {
        worst = ext_weights[f][i];
        spike = extrinsic.faces[f][i];
      }
    }
  ASSERT_LT(worst, -1e-3 * largest) << "the skinny sphere should have clearly negative cotan weights";

  IntrinsicTriangulation triangulation(input);
  triangulation.flip_to_delaunay();
  const IntrinsicMesh flipped = triangulation.snapshot();
  ASSERT_EQ(flipped.vertex_count, extrinsic.vertex_count);
  const auto flipped_weights = cotan_edge_weights(flipped);
  for (int f = 0; f < flipped.face_count(); ++f)
    for (int i = 0; i < 3; ++i) EXPECT_GE(flipped_weights[f][i], -1e-10 * largest) << "face " << f << " edge " << i;

  const SurfaceDomain ext_domain = build_surface_domain(extrinsic);
  const SurfaceDomain int_domain = build_surface_domain(flipped);
  EXPECT_NEAR(int_domain.total_area, ext_domain.total_area, 1e-9 * ext_domain.total_area);  // flips keep the surface
  double ext_min = 0.0;
  for (double dt : {1e-4, 1e-3, 1e-2, 1e-1, 1.0}) {
    EXPECT_GE(min_after_backward_euler(int_domain, spike, dt), -1e-12) << "dt " << dt;
    ext_min = std::min(ext_min, min_after_backward_euler(ext_domain, spike, dt));
  }
  EXPECT_LT(ext_min, -1e-6) << "the extrinsic Laplacian should violate the maximum principle for some dt";
}

}  // namespace
}  // namespace physarum
