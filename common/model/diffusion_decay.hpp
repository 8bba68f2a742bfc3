#pragma once
// The diffusion-decay field model (paper Eq. 1): du/dt = -M^-1 R_dif L u - R_dec u + s, with the
// cotan Laplacian L and lumped mass M of the intrinsic triangulation and the per-vertex rates of the
// parameter table (diffuse_rate, decay_rate). Both backends implement it (reference/diffusion_decay,
// opencl/diffusion_decay); what they must agree on lives here: the explicit scheme's stability limit (so
// both take the same sub-steps) and where a step's deposits enter.
#include "common/numerics/csr_matrix.hpp"
#include "common/numerics/time_integrator.hpp"
#include "common/base/element_data.hpp"

namespace physarum {

// How the step's deposits (the source term s) enter, consistently with each scheme. Forward Euler
// evaluates the source explicitly, u' = (I - dt R) u + dt s: transport first, then add the
// deposits. Backward Euler evaluates everything at the new time, (I + dt R) u' = u + dt s: add the
// deposits, then solve. With one forward sub-step or backward Euler, the total amount obeys
// m' = (1 - k dt) m + D resp. (1 + k dt) m' = m + D, whose fixed point is exactly D / (k dt): the
// steady-state mean is U (Eq. 5) in expectation, not U (1 +- k dt). Forward Euler in several
// sub-steps lands above U: common/model/discrete_steady_state.hpp says by how much.
enum class DepositOrder { AfterTransport, BeforeTransport };
DepositOrder deposit_order(Integrator integrator);

// How long one forward-Euler step (Eq. 6) may be. One sub-step is u' = u - h (M^-1 R_dif L u + R_dec u),
// i.e. row i:
//   u'_i = (1 - h a_i) u_i + h (r_dif,i / m_i) sum_j w_ij u_j,   a_i = r_dif,i L_ii / m_i + r_dec,i.
// (1) Non-negativity: with non-negative cotan weights w_ij (intrinsic Delaunay), every coefficient
//     is >= 0, so u stays >= 0, iff h a_i <= 1 for all i.
// (2) Stability: the eigenvalues of M^-1 R_dif L + R_dec are real and >= 0 (the matrix is similar
//     to a symmetric PSD one plus a non-negative diagonal); Gershgorin bounds the largest by
//     g = max_i (r_dif,i sum_j |L_ij| / m_i + r_dec,i), and the step is stable when h g <= 2.
//     (1) implies (2) when all weights are >= 0; (2) still holds the field bounded when a
//     triangulation has negative weights (non-Delaunay input), where (1) alone is not enough.
// A safety factor of 0.9 keeps rounding away from the edge of both bounds.
// Returns 0.9 min(1 / max a_i, 2 / g); +infinity when nothing diffuses or decays.
double forward_euler_stable_step(const CsrMatrix& laplacian, const IntrinsicVertexData<double>& diffuse_over_mass,
                                 const IntrinsicVertexData<double>& decay_rate);

// Sub-steps that split `time_step` into pieces no longer than `stable_step` (at least 1).
int forward_euler_sub_steps(double time_step, double stable_step);

}  // namespace physarum
