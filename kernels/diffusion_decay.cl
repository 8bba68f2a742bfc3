/* The pheromone field on the device (mirrors reference/diffusion_decay.cpp): Eq. 6 forward Euler
 * sub-steps, and the right-hand side of Eq. 7 backward Euler, whose system conjugate_gradients.cl
 * solves. float32 throughout: not every device has fp64.
 * Every per-vertex kernel runs on a global size padded to the work-group size, hence the guards. */
#include "deposit_cells.h"
#include "device_types.h"
#include "sparse_rows.h"

/* One forward Euler sub-step of Eq. 6 divided by M, for row i:
 *   u_out = F u_in,  F = I - h (diag(r_dif / m) L + diag(r_dec)),
 * with F assembled once on the host (common/model/pheromone_operators.hpp) in hybrid ELL + CSR form
 * (opencl/hybrid_matrix.hpp). Folding the rates into F leaves one matrix-vector product per
 * sub-step, which reads fewer bytes per vertex than L, two rate arrays and u_i would. This kernel
 * does the ELL block: a fixed loop of PHYSARUM_ELL_WIDTH slots, read slot-major so that adjacent
 * work-items read adjacent words and a CPU device can run it as gathers across work-items; it runs
 * on all `stride` rows of the block (padding rows have zero weights) and writes only the real ones.
 * pheromone_forward_overflow then adds the entries of the few longer rows. sub_step numbers the
 * sub-steps of one time step; only the planted fault no-decay-substep reads it, and decay_rate and h
 * with it, to add the first sub-step's decay back. */
__kernel void pheromone_forward_substep(const uint n, const uint stride, __global const int* column,
                                        __global const float* value, __global const float* decay_rate,
                                        const float h, __global const float* u_in, __global float* u_out,
                                        const uint sub_step) {
  const uint i = get_global_id(0);
  float sum = 0.0f;
#pragma unroll
  for (uint k = 0; k < PHYSARUM_ELL_WIDTH; ++k) sum += value[k * stride + i] * u_in[column[k * stride + i]];
#ifdef PHYSARUM_FAULT_NO_DECAY_SUBSTEP
  if (sub_step == 0 && i < n) sum += h * decay_rate[i] * u_in[i]; /* planted fault: the first sub-step skips decay */
#else
  (void)decay_rate, (void)h, (void)sub_step;
#endif
  if (i < n) u_out[i] = sum;
}

/* The rest of the forward sub-step: each row with more than PHYSARUM_ELL_WIDTH entries adds its
 * remaining ones (CSR, one work-item per long row, so no two work-items touch one vertex). */
__kernel void pheromone_forward_overflow(const uint count, __global const int* row, __global const int* row_start,
                                         __global const int* column, __global const float* value,
                                         __global const float* u_in, __global float* u_out) {
  const uint j = get_global_id(0);
  if (j >= count) return;
  u_out[row[j]] += csr_row_times(j, row_start, column, value, u_in);
}

/* Deposits into the field: u_i += amount_i / m_i, amount_i the accumulated cell (deposit_cells.h)
 * over the fixed-point scale, and the accumulator cleared for the next step (mirrors
 * ReferenceDiffusionDecay::add_deposits). */
__kernel void pheromone_add_deposits(const int n, __global PhysarumDepositCell* deposits,
                                     __global const float* inverse_mass, const float inverse_scale,
                                     __global float* concentration) {
  const int i = get_global_id(0);
  if (i >= n) return;
#ifdef PHYSARUM_FLOAT_DEPOSITS
  const float amount = deposits[i];
  deposits[i] = 0.0f;
#else
  const float amount = convert_float(deposits[i]) * inverse_scale;
  deposits[i] = 0;
#endif
  concentration[i] += amount * inverse_mass[i];
}

/* y = A x (the backward Euler right-hand side b = B u, and the whole step when the system is diagonal). */
__kernel void csr_multiply(const uint n, __global const int* row_start, __global const int* column,
                           __global const float* value, __global const float* x, __global float* y) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  y[i] = csr_row_times(i, row_start, column, value, x);
}

/* The write-stimuli of Sec. 3.3 (mirrors ReferenceDiffusionDecay): u_i += h w_i, a source term of
 * the PDE in concentration per second, then, when `clamp_at_zero`, u_i = max(u_i, 0). Forward Euler
 * runs it after every sub-step with h the sub-step and the clamp; backward Euler runs it before the
 * solve with h = dt and no clamp (the right-hand side M (u + dt w)), and after it with h = 0 and the
 * clamp. Launched only when the controls have a write rate. */
__kernel void pheromone_add_source(const int n, const float h, __global const float* rate, const int clamp_at_zero,
                                   __global float* u) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const float value = u[i] + h * rate[i];
  u[i] = clamp_at_zero ? fmax(value, 0.0f) : value;
}
