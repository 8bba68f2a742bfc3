// Smallest eigenvalues of L x = lambda M x: the sphere's spherical harmonics, and known values of
// spot's intrinsic Delaunay triangulation computed by an independent implementation.
#include "common/surface/eigenvalues.hpp"
#include "common/base/errors.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/surface/surface_domain.hpp"
#include "tests/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace physarum {
namespace {

TEST(Eigenvalues, UnitSphereHasTheSphericalHarmonicSpectrum) {
  // Continuous unit sphere: l (l + 1) with multiplicity 2 l + 1, i.e. 0, 2 (x3), 6 (x5), 12 (x7), 20 (x9).
  const InputMesh sphere = load_mesh("shape:sphere");
  ASSERT_EQ(sphere.vertex_count(), 2562);
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(sphere));
  const std::vector<double> lambda = smallest_eigenvalues(d, 17);
  ASSERT_EQ(lambda.size(), 17u);
  EXPECT_NEAR(lambda[0], 0.0, 1e-8);
  int index = 1;
  for (int l = 1; l <= 3; ++l) {
    const double exact = l * (l + 1.0);
    for (int m = 0; m < 2 * l + 1; ++m, ++index)
      EXPECT_NEAR(lambda[index], exact, 0.01 * exact) << "eigenvalue " << index << " (l = " << l << ")";
  }
  EXPECT_NEAR(lambda[16], 20.0, 0.02 * 20.0);  // the first of l = 4: multiplicity 7 of l = 3 is exact
  for (size_t i = 1; i < lambda.size(); ++i) EXPECT_LE(lambda[i - 1], lambda[i]);
}

TEST(Eigenvalues, EigenvectorsSolveTheGeneralizedProblemAndAreMassOrthonormal) {
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(load_mesh("shape:sphere")));
  const Eigenpairs pairs = smallest_eigenpairs(d, 6);
  ASSERT_EQ(pairs.vectors.cols(), 6);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> l = d.laplacian.to_eigen();
  const Eigen::VectorXd mass = Eigen::Map<const Eigen::VectorXd>(d.vertex_mass.data(), d.vertex_count);
  for (int k = 0; k < 6; ++k) {
    const Eigen::VectorXd x = pairs.vectors.col(k);
    const Eigen::VectorXd residual = l * x - pairs.values[k] * mass.cwiseProduct(x);
    EXPECT_LT(residual.norm(), 1e-8 * std::max(1.0, pairs.values[k])) << "pair " << k;
    for (int j = 0; j < 6; ++j)
      EXPECT_NEAR(x.dot(mass.cwiseProduct(pairs.vectors.col(j))), j == k ? 1.0 : 0.0, 1e-9);
  }
  // The zero mode is constant.
  const Eigen::VectorXd x0 = pairs.vectors.col(0);
  EXPECT_LT((x0.array() - x0.mean()).abs().maxCoeff(), 1e-8 * std::abs(x0.mean()));
}

TEST(Eigenvalues, SpotIntrinsicDelaunayMatchesAnIndependentImplementation) {
  PHYSARUM_REQUIRE_SHARED_MESH(path, "spot.obj");
  // Intrinsic Delaunay triangulation (flips only) of spot.obj, lumped mass: the 12 smallest
  // eigenvalues as computed by an independent implementation.
  const double expected[12] = {0.0,         1.591643482, 4.636215312, 6.734794177, 8.290285639, 10.74691638,
                               10.84904529, 12.10472968, 15.30060788, 17.39286376, 21.40352209, 24.8476668};
  const InputMesh input = load_mesh(path);
  IntrinsicTriangulation triangulation(input);
  triangulation.flip_to_delaunay();
  const SurfaceDomain intrinsic = build_surface_domain(triangulation.snapshot());
  const std::vector<double> lambda = smallest_eigenvalues(intrinsic, 12);
  ASSERT_EQ(lambda.size(), 12u);
  EXPECT_NEAR(lambda[0], 0.0, 1e-8);
  for (int k = 1; k < 12; ++k) EXPECT_NEAR(lambda[k], expected[k], 1e-6 * expected[k]) << "eigenvalue " << k;

  // The extrinsic mesh (no flips) has a close but different spectrum: the comparison above really
  // depends on the flips.
  const std::vector<double> extrinsic = smallest_eigenvalues(build_surface_domain(intrinsic_mesh_from_input(input)), 12);
  double largest_difference = 0.0;
  for (int k = 1; k < 12; ++k) {
    EXPECT_NEAR(extrinsic[k], expected[k], 0.05 * expected[k]);
    largest_difference = std::max(largest_difference, std::abs(extrinsic[k] - expected[k]) / expected[k]);
  }
  EXPECT_GT(largest_difference, 1e-5);
}

TEST(Eigenvalues, RejectsMismatchedOrNonPositiveMass) {
  const SurfaceDomain d = build_surface_domain(intrinsic_mesh_from_input(load_mesh("shape:sphere")));
  IntrinsicVertexData<double> mass = d.vertex_mass;
  mass[7] = 0.0;
  EXPECT_THROW(smallest_eigenvalues(d.laplacian, mass, 4), InputError);
  mass.values().pop_back();
  EXPECT_THROW(smallest_eigenvalues(d.laplacian, mass, 4), InputError);
}

}  // namespace
}  // namespace physarum
