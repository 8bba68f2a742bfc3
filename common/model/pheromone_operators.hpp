#pragma once
// The operators of the pheromone PDE (Eq. 6 and Eq. 7) assembled in double from the cotan Laplacian
// L, the lumped masses and the per-vertex rates, in the forms a sparse matrix-vector kernel wants:
// pure functions, so they can be checked against dense Eigen equivalents (tests/test_pheromone_operators.cpp).
// The OpenCL backend converts them to float when it uploads them (opencl/diffusion_decay.cpp).
#include "common/numerics/csr_matrix.hpp"
#include "common/base/element_data.hpp"

#include <vector>

namespace physarum {

// The forward Euler sub-step matrix of Eq. 6 divided by M, for sub-step h:
//   F = I - h (diag(r_dif / m) L + diag(r_dec)),
// with L's sparsity (a row of L without a stored diagonal entry gets one, at the row's end).
CsrMatrix forward_substep_matrix(const CsrMatrix& L, const IntrinsicVertexData<double>& diffuse_over_mass,
                                 const IntrinsicVertexData<double>& decay_rate, double h);

// Eq. 7, [M + dt (R_dif L + R_dec M)] u' = M u, as S u' = B u with S symmetric positive definite
// (what conjugate gradients needs) even where R_dif varies:
//  * a vertex with r_dif,i > 0 ("active") has its row divided by r_dif,i:
//      m_i (1 + dt r_dec,i) / r_dif,i u'_i + dt sum_j L_ij u'_j = m_i u_i / r_dif,i,
//    whose matrix diag(m (1 + dt r_dec) / r_dif) + dt L is symmetric (L is) and positive definite
//    (positive diagonal plus a PSD Laplacian). A uniform R_dif is the special case of one scale.
//  * a vertex with r_dif,i = 0 does not diffuse: u'_i = u_i / (1 + dt r_dec,i), known up front, so
//    its row becomes the identity and its column's terms in active rows move to the right-hand
//    side (-dt L_ij u_j / (1 + dt r_dec,j)). Keeping only active-active couplings keeps S symmetric.
struct BackwardEulerSystem {
  CsrMatrix system;                      // S: same sparsity as L among active vertices, identity rows elsewhere
  CsrMatrix rhs;                         // B: the right-hand-side operator, mostly diagonal
  std::vector<double> inverse_diagonal;  // 1 / S_ii (the Jacobi preconditioner); 1 on identity rows
  bool diagonal_only = false;            // no vertex diffuses: S = I, and B u is the solution
};
BackwardEulerSystem backward_euler_system(const CsrMatrix& L, const IntrinsicVertexData<double>& mass,
                                          const IntrinsicVertexData<double>& diffuse_rate,
                                          const IntrinsicVertexData<double>& decay_rate, double dt);

}  // namespace physarum
