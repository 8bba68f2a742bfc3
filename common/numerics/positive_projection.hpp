#pragma once
// Making an element's Hessian positive semidefinite, so that Newton's method on a nonconvex energy
// (a buckling shell) always steps downhill: the nearest such matrix in the Frobenius norm, the
// symmetric matrix's eigen-decomposition with every negative eigenvalue set to zero (Teran et al.
// 2005). (Their absolute values instead, as Chen, Diaz & Yuksel 2024 suggest, took 2-30 times more
// Newton iterations on our growing disks; so did a cheaper convex approximation without
// eigen-decompositions, the membrane's compressive stress and the hinge's angle curvature dropped:
// the cap of tests/test_shell_equilibrium.cpp took 186 s instead of 2 s and did not converge.)
#include <Eigen/Eigenvalues>

#include <cmath>

namespace physarum {

// An orthonormal basis of the motions of `Corners` points in 3D that are not translations: the
// columns of Q (x) I3, where Q (Corners x Corners-1) holds the columns after the first of the
// Householder reflection that takes (1, ..., 1) / sqrt(Corners) to the first unit vector.
template <int Corners>
Eigen::Matrix<double, 3 * Corners, 3 * (Corners - 1)> non_translation_basis() {
  Eigen::Matrix<double, Corners, 1> v = Eigen::Matrix<double, Corners, 1>::Constant(1.0 / std::sqrt(double(Corners)));
  v(0) -= 1.0;
  const Eigen::Matrix<double, Corners, Corners> reflection =
      Eigen::Matrix<double, Corners, Corners>::Identity() - (2.0 / v.squaredNorm()) * v * v.transpose();
  Eigen::Matrix<double, 3 * Corners, 3 * (Corners - 1)> basis = Eigen::Matrix<double, 3 * Corners, 3 * (Corners - 1)>::Zero();
  for (int corner = 0; corner < Corners; ++corner)
    for (int k = 1; k < Corners; ++k) basis.template block<3, 3>(3 * corner, 3 * (k - 1)).diagonal().setConstant(reflection(corner, k));
  return basis;
}

// The projection of the Hessian of an energy of `Corners` points that moving all of them together
// does not change (a membrane triangle's, a hinge's). Such a Hessian is zero along the three
// translations, so its eigen-decomposition is that of the 3 (Corners - 1) matrix of the other
// directions: in exact arithmetic the same result as decomposing the whole matrix, at ~n^3 the
// cost (12 -> 9 for a hinge, 9 -> 6 for a triangle).
template <int Corners>
void make_positive_semidefinite(Eigen::Matrix<double, 3 * Corners, 3 * Corners>& matrix) {
  constexpr int kReduced = 3 * (Corners - 1);
  static const Eigen::Matrix<double, 3 * Corners, kReduced> basis = non_translation_basis<Corners>();
  // lazyProduct: coefficient loops, not the blocked product Eigen picks for these sizes (its packing
  // cost more than the arithmetic).
  const Eigen::Matrix<double, 3 * Corners, kReduced> half = matrix.lazyProduct(basis);
  Eigen::Matrix<double, kReduced, kReduced> reduced = basis.transpose().lazyProduct(half);
  reduced = (0.5 * (reduced + reduced.transpose())).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, kReduced, kReduced>> eigen(reduced);
  const auto& values = eigen.eigenvalues();
  if (values.minCoeff() >= 0.0) return;
  const Eigen::Matrix<double, kReduced, 1> filtered = values.cwiseMax(0.0);
  const Eigen::Matrix<double, 3 * Corners, kReduced> vectors = basis * eigen.eigenvectors();
  matrix = (vectors * filtered.asDiagonal()).lazyProduct(vectors.transpose());
}

}  // namespace physarum
