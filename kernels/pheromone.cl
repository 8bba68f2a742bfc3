/* The pheromone field on the device (mirrors reference/pheromone.cpp): Eq. 6 forward Euler
 * sub-steps, and Eq. 7 backward Euler solved by Jacobi-preconditioned conjugate gradients whose
 * scalars stay in a PhysarumCgState on the device. float32 throughout: not every device has fp64.
 * Every per-vertex kernel runs on a global size padded to the work-group size, hence the guards. */
#include "device_types.h"
#include "reduction.h"

/* (A x)_i for a CSR matrix: the loop is bounded by the row's length. */
float csr_row_times(const uint i, __global const int* row_start, __global const int* column,
                    __global const float* value, __global const float* x) {
  float sum = 0.0f;
  const int end = row_start[i + 1];
  for (int k = row_start[i]; k < end; ++k) sum += value[k] * x[column[k]];
  return sum;
}

/* One forward Euler sub-step of Eq. 6 divided by M, for row i:
 *   u_out = F u_in,  F = I - h (diag(r_dif / m) L + diag(r_dec)),
 * with F assembled once on the host (opencl/pheromone.cpp) in hybrid ELL + CSR form
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

/* Deposits: an amount at a vertex raises its concentration by amount / m_i. */
__kernel void pheromone_add_amounts(const uint n, __global const float* amount, __global const float* inverse_mass,
                                    __global float* u) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  u[i] += amount[i] * inverse_mass[i];
}

/* y = A x (the backward Euler right-hand side b = B u, and the whole step when the system is diagonal). */
__kernel void csr_multiply(const uint n, __global const int* row_start, __global const int* column,
                           __global const float* value, __global const float* x, __global float* y) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  y[i] = csr_row_times(i, row_start, column, value, x);
}

/* ---- conjugate gradients for S x = b, S symmetric positive definite, Jacobi preconditioner ----
 * Per iteration: cg_multiply (q = S p, partial p.q) -> cg_alpha -> cg_update (x, r, z, partial r.z
 * and r.r) -> cg_beta -> cg_direction (p = z + beta p). Once the state leaves RUNNING every kernel
 * leaves its outputs alone, so the host may enqueue several iterations ahead without reading
 * anything back. Kernels with barriers do not return early on that test even though it is uniform:
 * PoCL's work-item loops hang on a return before a barrier that depends on a global value, so they
 * run the (cheap) reduction of zeros and guard their writes instead. */

/* r = b - S x, z = D^-1 r, p = z; partials of (r.z, r.r, b.b). */
__kernel void cg_start(const uint n, __global const int* row_start, __global const int* column,
                       __global const float* value, __global const float* inverse_diagonal,
                       __global const float* b, __global const float* x, __global float* r, __global float* z,
                       __global float* p, __global float4* partials, __local float4* scratch) {
  const uint i = get_global_id(0);
  float4 mine = (float4)(0.0f);
  if (i < n) {
    const float ri = b[i] - csr_row_times(i, row_start, column, value, x);
    const float zi = inverse_diagonal[i] * ri;
    r[i] = ri;
    z[i] = zi;
    p[i] = zi;
    mine = (float4)(ri * zi, ri * ri, b[i] * b[i], 0.0f);
  }
  const float4 total = work_group_sum4(scratch, mine);
  if (get_local_id(0) == 0) partials[get_group_id(0)] = total;
}

__kernel void cg_start_finish(const uint count, __global const float4* partials, const float tolerance_squared,
                              __global PhysarumCgState* state, __local float4* scratch) {
  const float4 total = sum_partials4(partials, count, scratch);
  if (get_global_id(0) != 0) return;
  state->rz = total.x;
  state->rr = total.y;
  state->bb = total.z;
  state->stop_rr = tolerance_squared * total.z;
  state->pq = 0.0f;
  state->beta = 0.0f;
  state->iterations = 0;
  state->status = total.y <= state->stop_rr ? PHYSARUM_CG_CONVERGED : PHYSARUM_CG_RUNNING;
}

/* q = S p; partials of p.q. */
__kernel void cg_multiply(const uint n, __global const int* row_start, __global const int* column,
                          __global const float* value, __global const float* p, __global float* q,
                          __global const PhysarumCgState* state, __global float4* partials,
                          __local float4* scratch) {
  const bool running = state->status == PHYSARUM_CG_RUNNING;
  const uint i = get_global_id(0);
  float4 mine = (float4)(0.0f);
  if (running && i < n) {
    const float qi = csr_row_times(i, row_start, column, value, p);
    q[i] = qi;
    mine.x = p[i] * qi;
  }
  const float4 total = work_group_sum4(scratch, mine);
  if (running && get_local_id(0) == 0) partials[get_group_id(0)] = total;
}

__kernel void cg_alpha(const uint count, __global const float4* partials, __global PhysarumCgState* state,
                       __local float4* scratch) {
  const float4 total = sum_partials4(partials, count, scratch);
  // Only work-item 0 touches the state: another item reading it while item 0 writes it would be a
  // data race (the barriers order local memory only).
  if (get_global_id(0) != 0 || state->status != PHYSARUM_CG_RUNNING) return;
  state->pq = total.x;
  if (!(total.x > 0.0f)) state->status = PHYSARUM_CG_BREAKDOWN;
}

/* x += alpha p, r -= alpha q, z = D^-1 r; partials of (r.z, r.r). */
__kernel void cg_update(const uint n, __global const float* inverse_diagonal, __global const float* p,
                        __global const float* q, __global float* x, __global float* r, __global float* z,
                        __global const PhysarumCgState* state, __global float4* partials,
                        __local float4* scratch) {
  const bool running = state->status == PHYSARUM_CG_RUNNING;
  const uint i = get_global_id(0);
  float4 mine = (float4)(0.0f);
  if (running && i < n) {
    const float alpha = state->rz / state->pq;
    x[i] += alpha * p[i];
    const float ri = r[i] - alpha * q[i];
    const float zi = inverse_diagonal[i] * ri;
    r[i] = ri;
    z[i] = zi;
    mine.x = ri * zi;
    mine.y = ri * ri;
  }
  const float4 total = work_group_sum4(scratch, mine);
  if (running && get_local_id(0) == 0) partials[get_group_id(0)] = total;
}

__kernel void cg_beta(const uint count, __global const float4* partials, __global PhysarumCgState* state,
                      __local float4* scratch) {
  const float4 total = sum_partials4(partials, count, scratch);
  // Only work-item 0 touches the state: another item reading it while item 0 writes it would be a
  // data race (the barriers order local memory only).
  if (get_global_id(0) != 0 || state->status != PHYSARUM_CG_RUNNING) return;
  state->beta = total.x / state->rz;
  state->rz = total.x;
  state->rr = total.y;
  state->iterations += 1;
  if (total.y <= state->stop_rr) state->status = PHYSARUM_CG_CONVERGED;
}

/* p = z + beta p. */
__kernel void cg_direction(const uint n, __global const float* z, __global float* p,
                           __global const PhysarumCgState* state) {
  if (state->status != PHYSARUM_CG_RUNNING) return;
  const uint i = get_global_id(0);
  if (i >= n) return;
  p[i] = z[i] + state->beta * p[i];
}
