#pragma once
// Making an element's Hessian positive semidefinite, so that Newton's method on a nonconvex energy
// (a buckling shell) always steps downhill: the nearest such matrix in the Frobenius norm, the
// symmetric matrix's eigen-decomposition with every negative eigenvalue set to zero (Teran et al.
// 2005). (Their absolute values instead, as Chen, Diaz & Yuksel 2024 suggest, took 2-30 times more
// Newton iterations on our growing disks; so did a cheaper convex approximation without
// eigen-decompositions, the membrane's compressive stress and the hinge's angle curvature dropped:
// the cap of tests/test_shell_equilibrium.cpp took 186 s instead of 2 s and did not converge.)
#include <Eigen/Eigenvalues>

namespace physarum {

template <int N>
void make_positive_semidefinite(Eigen::Matrix<double, N, N>& matrix) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(matrix);
  const auto& values = eigen.eigenvalues();
  if (values.minCoeff() >= 0.0) return;
  const Eigen::Matrix<double, N, 1> filtered = values.cwiseMax(0.0);
  matrix = eigen.eigenvectors() * filtered.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace physarum
