// Surface domain: face layouts, transitions between face frames, areas, lumped mass and the cotan
// Laplacian, on small meshes built inline (flat grids, an irregular flat mesh, an icosphere).
#include "common/base/errors.hpp"
#include "common/surface/fe_operators.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/surface/surface_domain.hpp"
#include "pheromone_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <map>
#include <random>

namespace physarum {
namespace {

using testing::make_icosphere;
using testing::make_square_grid;

double extrinsic_area(const InputMesh& m) {
  double a = 0.0;
  for (const auto& t : m.triangles)
    a += 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm();
  return a;
}

TEST(SurfaceDomain, LayoutsReproduceEdgeLengthsAndAreCounterClockwise) {
  const IntrinsicMesh mesh = intrinsic_mesh_from_input(make_icosphere(2));
  const SurfaceDomain d = build_surface_domain(mesh);
  ASSERT_EQ(d.face_count, mesh.face_count());
  for (int f = 0; f < d.face_count; ++f) {
    const auto& c = d.face_corners[f];
    EXPECT_EQ(c[0], Eigen::Vector2d::Zero());
    EXPECT_EQ(c[1].y(), 0.0);
    EXPECT_GT(c[1].x(), 0.0);
    EXPECT_GT(c[2].y(), 0.0);
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR((c[(i + 1) % 3] - c[i]).norm(), mesh.edge_lengths[f][i], 1e-14) << "face " << f << " edge " << i;
    EXPECT_NEAR(d.face_area[f], 0.5 * c[1].x() * c[2].y(), 1e-15);
  }
}

TEST(SurfaceDomain, TransitionsCarrySharedEdgesOntoTheNeighbour) {
  for (const InputMesh& input : {make_icosphere(2), make_square_grid(6, true, 0.3)}) {
    const IntrinsicMesh mesh = intrinsic_mesh_from_input(input);
    const SurfaceDomain d = build_surface_domain(mesh);
    int interior = 0;
    for (int f = 0; f < d.face_count; ++f)
      for (int i = 0; i < 3; ++i) {
        const int g = d.face_neighbour[f][i];
        const Rotation2& t = d.edge_transition[3 * f + i];
        if (g < 0) {
          EXPECT_EQ(mesh.twin[f][i], -1);
          EXPECT_EQ(t.cos_angle, 1.0);
          EXPECT_EQ(t.sin_angle, 0.0);
          continue;
        }
        ++interior;
        const int j = d.neighbour_edge[f][i];
        EXPECT_EQ(mesh.twin[f][i], 3 * g + j);
        // The edge a -> b turns into a' -> b', reversed in the neighbour (corner j+1 -> corner j).
        const Eigen::Vector2d edge = d.face_corners[f][(i + 1) % 3] - d.face_corners[f][i];
        const Eigen::Vector2d edge_there = d.face_corners[g][j] - d.face_corners[g][(j + 1) % 3];
        EXPECT_LT((t.apply_direction(edge) - edge_there).norm(), 1e-12);
        EXPECT_NEAR(t.cos_angle * t.cos_angle + t.sin_angle * t.sin_angle, 1.0, 1e-14);
        // Composing with the twin's transition is the identity.
        const Rotation2& back = d.edge_transition[3 * g + j];
        for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.3, -0.7), Eigen::Vector2d(2.0, 5.0)}) {
          EXPECT_LT((back.apply_direction(t.apply_direction(p)) - p).norm(), 1e-12);
        }
      }
    EXPECT_GT(interior, 0);
  }
}

TEST(SurfaceDomain, AreasAndMassSumToTheSurfaceArea) {
  for (const InputMesh& input : {make_icosphere(3), make_square_grid(5, false, 0.3)}) {
    const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(input));
    double face_sum = 0.0, mass_sum = 0.0;
    for (double a : d.face_area) face_sum += a;
    for (double m : d.vertex_mass) mass_sum += m;
    const double expected = extrinsic_area(input);
    EXPECT_NEAR(face_sum, expected, 1e-12 * expected);
    EXPECT_NEAR(d.total_area, expected, 1e-12 * expected);
    EXPECT_NEAR(mass_sum, expected, 1e-12 * expected);
  }
  // The flat unit square has area exactly 1; a corner vertex with one incident face gets 1/3 of it.
  const SurfaceDomain square = build_surface_domain(intrinsic_mesh_from_input(make_square_grid(4, false)));
  EXPECT_NEAR(square.total_area, 1.0, 1e-14);
  EXPECT_NEAR(square.vertex_mass[4], (1.0 / 32.0) / 3.0, 1e-16);  // corner (1, 0): one face of area 1/32
}

TEST(SurfaceDomain, LaplacianIsSymmetricWithZeroRowSumsAndPositiveSemiDefinite) {
  // The jittered mixed grid has obtuse triangles, hence negative edge weights: PSD must still hold.
  for (const InputMesh& input : {make_icosphere(1), make_square_grid(6, true, 0.45, 7)}) {
    const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(input));
    const Eigen::MatrixXd l = Eigen::MatrixXd(d.laplacian.to_eigen());
    ASSERT_EQ(l.rows(), d.vertex_count);
    EXPECT_LT((l - l.transpose()).cwiseAbs().maxCoeff(), 1e-13);
    std::vector<double> ones(d.vertex_count, 1.0), y;
    d.laplacian.multiply(ones, y);
    for (double v : y) EXPECT_NEAR(v, 0.0, 1e-12);
    const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(l).eigenvalues();
    EXPECT_GE(eig.minCoeff(), -1e-9 * eig.maxCoeff());
    EXPECT_GT(eig.maxCoeff(), 0.0);
    // Exactly one zero eigenvalue per connected component (both meshes are connected).
    EXPECT_GT(eig[1], 1e-6 * eig.maxCoeff());
  }
}

// Edges of an intrinsic mesh that a simple-graph view gets wrong: self-loops (both ends the same
// vertex) and parallel edges (two different edges between the same two vertices).
struct MultigraphEdges {
  int self_loops = 0;
  int parallel = 0;
};
MultigraphEdges multigraph_edges(const IntrinsicMesh& mesh) {
  MultigraphEdges r;
  std::map<std::pair<int, int>, int> edges_between;  // vertex pair -> number of distinct edges
  for (int f = 0; f < mesh.face_count(); ++f)
    for (int i = 0; i < 3; ++i) {
      const int h = 3 * f + i, twin = mesh.twin[f][i];
      if (twin >= 0 && twin < h) continue;  // count each edge once
      const int a = mesh.faces[f][i], b = mesh.faces[f][(i + 1) % 3];
      if (a == b) ++r.self_loops;
      if (++edges_between[std::minmax(a, b)] == 2) ++r.parallel;
    }
  return r;
}

// Dirichlet energy of the piecewise-linear function u, the integral of |grad u|^2: sum over faces of
// area_f |grad_f u|^2, with each gradient from the face's own 2D layout. With the weights
// w = (cot a + cot b) / 2 of surface_domain.hpp, u^T L u = sum over edges w (u_i - u_j)^2 equals it
// exactly, whatever the vertex ids (a self-loop contributes 0, parallel edges each their own term).
double face_gradient_energy(const SurfaceDomain& d, const std::vector<double>& u) {
  double energy = 0.0;
  for (int f = 0; f < d.face_count; ++f) {
    const auto& c = d.face_corners[f];
    Eigen::Matrix2d edges;
    edges << (c[1] - c[0]).transpose(), (c[2] - c[0]).transpose();
    const auto& v = d.face_vertices[f];
    const Eigen::Vector2d differences(u[v[1]] - u[v[0]], u[v[2]] - u[v[0]]);
    const Eigen::Vector2d gradient = edges.inverse() * differences;
    energy += d.face_area[f] * gradient.squaredNorm();
  }
  return energy;
}

// A closed cone: apex above an n-gon rim, closed by a fan around the base centre.
InputMesh closed_cone(int n, double height, double radius) {
  InputMesh m;
  m.source = "test:cone";
  m.positions.emplace_back(0.0, 0.0, height);
  m.positions.emplace_back(0.0, 0.0, 0.0);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    m.positions.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
  }
  for (int k = 0; k < n; ++k) {
    const int r0 = 2 + k, r1 = 2 + (k + 1) % n;
    m.triangles.push_back({0, r0, r1});
    m.triangles.push_back({1, r1, r0});
  }
  return m;
}

// The invariants of the Laplacian test above, on REFINED intrinsic triangulations (flips plus
// circumcenter insertion): a closed 8-sided cone, whose sharp apex (angle sum ~1.5 rad) makes the
// Delaunay triangulation wrap edges around it -- a self-loop and parallel edges, counted below --
// and the shipped octagonal prism.
TEST(SurfaceDomain, LaplacianInvariantsHoldOnRefinedIntrinsicTriangulations) {
  for (const auto& [input, radius] : {std::pair{closed_cone(8, 2.0, 0.5), 0.1},
                                      std::pair{load_mesh("shape:octagonal-prism"), 0.1}}) {
    const std::string& shape = input.source;
    SCOPED_TRACE(shape);
    IntrinsicTriangulation tri(input);
    tri.flip_to_delaunay();
    RefinementOptions options;
    options.max_circumradius = radius;
    const RefinementResult refined = tri.refine(options);
    const IntrinsicMesh mesh = tri.snapshot();
    const MultigraphEdges here = multigraph_edges(mesh);
    std::cout << shape << ": " << mesh.vertex_count << " vertices, " << refined.insertions() << " insertions, "
              << here.self_loops << " self-loops, " << here.parallel << " parallel edges\n";
    if (shape == "test:cone") {
      EXPECT_GT(here.self_loops, 0);
      EXPECT_GT(here.parallel, 0);
    }
    EXPECT_GT(refined.insertions(), 0u);
    ASSERT_LT(mesh.vertex_count, 3000) << "keep the dense eigen-solve small";

    const SurfaceDomain d = build_surface_domain(mesh);
    const Eigen::MatrixXd l = Eigen::MatrixXd(d.laplacian.to_eigen());
    EXPECT_LT((l - l.transpose()).cwiseAbs().maxCoeff(), 1e-12 * l.cwiseAbs().maxCoeff());
    std::vector<double> ones(d.vertex_count, 1.0), y;
    d.laplacian.multiply(ones, y);
    for (double v : y) EXPECT_NEAR(v, 0.0, 1e-12 * l.cwiseAbs().maxCoeff());
    const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(l).eigenvalues();
    EXPECT_GE(eig.minCoeff(), -1e-9 * eig.maxCoeff());
    EXPECT_GT(eig[1], 1e-6 * eig.maxCoeff()) << "one zero eigenvalue: the surface is connected";
    // The quadratic form is the Dirichlet energy: every edge, parallel or not, counted once.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (int trial = 0; trial < 3; ++trial) {
      std::vector<double> u(d.vertex_count), lu;
      for (double& x : u) x = uniform(rng);
      d.laplacian.multiply(u, lu);
      double form = 0.0;
      for (int i = 0; i < d.vertex_count; ++i) form += u[i] * lu[i];
      const double energy = face_gradient_energy(d, u);
      EXPECT_NEAR(form, energy, 1e-9 * energy);
    }
  }
}

TEST(SurfaceDomain, LaplacianHasLinearPrecisionOnFlatMeshes) {
  // Any planar mesh, however irregular: L applied to a linear function vanishes at interior vertices.
  for (const InputMesh& input : {make_square_grid(8, false), make_square_grid(8, true, 0.4, 3)}) {
    const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(input));
    std::vector<double> u(d.vertex_count), lu;
    for (int v = 0; v < d.vertex_count; ++v) u[v] = 2.0 * input.positions[v].x() - 3.0 * input.positions[v].y() + 0.5;
    d.laplacian.multiply(u, lu);
    int checked = 0;
    for (int v = 0; v < d.vertex_count; ++v) {
      const Eigen::Vector3d& p = input.positions[v];
      if (p.x() <= 0.0 || p.x() >= 1.0 || p.y() <= 0.0 || p.y() >= 1.0) continue;
      EXPECT_NEAR(lu[v], 0.0, 1e-12) << "vertex " << v;
      ++checked;
    }
    EXPECT_EQ(checked, 7 * 7);
  }
}

TEST(SurfaceDomain, LaplacianMatchesTheKnownStencilOnARegularGrid) {
  // Right isosceles triangles with all diagonals parallel: the cotan Laplacian is the 5-point
  // stencil (diagonal edges have weight 0, axis edges weight 1), independent of the cell size.
  const int n = 4;
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(make_square_grid(n, false)));
  const Eigen::MatrixXd l = Eigen::MatrixXd(d.laplacian.to_eigen());
  const int centre = 2 * (n + 1) + 2;
  EXPECT_NEAR(l(centre, centre), 4.0, 1e-12);
  for (int neighbour : {centre - 1, centre + 1, centre - (n + 1), centre + (n + 1)})
    EXPECT_NEAR(l(centre, neighbour), -1.0, 1e-12);
  EXPECT_NEAR(l(centre, centre + n + 2), 0.0, 1e-12);  // along the diagonal
}

TEST(SurfaceDomain, BarycentricCoordinatesOfCornersAndCentroid) {
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(make_icosphere(1)));
  for (int f = 0; f < d.face_count; f += 7) {
    const auto& c = d.face_corners[f];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d b = barycentric_in_face(d, f, c[k]);
      for (int m = 0; m < 3; ++m) EXPECT_NEAR(b[m], k == m ? 1.0 : 0.0, 1e-14);
    }
    const Eigen::Vector2d p = 0.2 * c[0] + 0.3 * c[1] + 0.5 * c[2];
    EXPECT_LT((barycentric_in_face(d, f, p) - Eigen::Vector3d(0.2, 0.3, 0.5)).norm(), 1e-14);
  }
}

TEST(SurfaceDomain, FaceSamplerIsProportionalToAreaTimesWeight) {
  const InputMesh input = make_square_grid(2, false, 0.0);
  const IntrinsicMesh mesh = intrinsic_mesh_from_input(input);
  IntrinsicFaceData<double> weight(mesh.face_count(), 1.0);
  weight[0] = 0.0;
  weight[3] = 3.0;
  const SurfaceDomain d = build_surface_domain(mesh, weight);
  std::vector<double> p(d.face_count, 0.0);
  const int n = d.face_sampler.size();
  ASSERT_EQ(n, d.face_count);
  for (int i = 0; i < n; ++i) {
    p[i] += d.face_sampler.probability[i] / n;
    p[d.face_sampler.alias[i]] += (1.0 - d.face_sampler.probability[i]) / n;
  }
  // All 8 faces have area 1/8; weights sum to 0 + 3 + 6 * 1 = 9.
  for (int f = 0; f < d.face_count; ++f) EXPECT_NEAR(p[f], weight[f] / 9.0, 1e-12);
  weight[2] = -1.0;
  EXPECT_THROW(build_surface_domain(mesh, weight), InputError);
  EXPECT_THROW(build_surface_domain(mesh, IntrinsicFaceData<double>(3, 1.0)), InputError);
}

TEST(SurfaceDomain, RejectsImpossibleTrianglesNamingTheFace) {
  IntrinsicMesh mesh = intrinsic_mesh_from_input(make_square_grid(2, false));
  mesh.edge_lengths[5] = {1.0, 1.0, 2.5};  // violates the triangle inequality
  try {
    build_surface_domain(mesh);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 5"), std::string::npos) << e.what();
  }
  mesh = intrinsic_mesh_from_input(make_square_grid(2, false));
  mesh.edge_lengths[3] = {1.0, 0.5, 0.5};  // degenerate: zero area
  EXPECT_THROW(build_surface_domain(mesh), InputError);
  mesh = intrinsic_mesh_from_input(make_square_grid(2, false));
  mesh.edge_lengths[1][0] = 0.0;
  EXPECT_THROW(build_surface_domain(mesh), InputError);
}

}  // namespace
}  // namespace physarum
