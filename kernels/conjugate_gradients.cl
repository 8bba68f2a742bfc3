/* Conjugate gradients for S x = b on the device, S symmetric positive definite (the backward Euler
 * system of Eq. 7, common/model/pheromone_operators.hpp), Jacobi preconditioner; the solver's scalars stay
 * in a PhysarumCgState on the device (host side: opencl/conjugate_gradients.cpp). float32
 * throughout. Every per-vertex kernel runs on a global size padded to the work-group size, hence the
 * guards.
 *
 * Per iteration: cg_multiply (q = S p, partial p.q) -> cg_alpha -> cg_update (x, r, z, partial r.z
 * and r.r) -> cg_beta -> cg_direction (p = z + beta p). Once the state leaves RUNNING every kernel
 * leaves its outputs alone, so the host may enqueue several iterations ahead without reading
 * anything back. Kernels with barriers do not return early on that test even though it is uniform:
 * PoCL's work-item loops hang on a return before a barrier that depends on a global value, so they
 * run the (cheap) reduction of zeros and guard their writes instead. */
#include "device_types.h"
#include "reduction.h"
#include "sparse_rows.h"

/* Whether this work-item of a one-group pass writes the state: only work-item 0 touches it (another
 * item reading it while item 0 writes it would be a data race; the barriers order local memory
 * only), and only while the solve runs. */
bool updates_state(__global const PhysarumCgState* state) {
  return get_global_id(0) == 0 && state->status == PHYSARUM_CG_RUNNING;
}

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
  if (!updates_state(state)) return;
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
  if (!updates_state(state)) return;
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
