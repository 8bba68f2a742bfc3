/* Reaction-diffusion on the device (opencl/reaction_diffusion.hpp; the equations are those of
 * common/reaction_diffusion/reaction_diffusion_system.hpp): explicit sub-steps fused over all morphogens, and the
 * right-hand side of the IMEX step. float32 throughout: not every device has fp64.
 *
 * The host prepends a generated prelude (opencl/reaction_diffusion.cpp) that defines
 *   RD_MORPHOGENS         the number of morphogens, 2..8
 *   RD_LOAD_COEFFICIENTS  statements reading the coefficients that vary per vertex into locals
 *                         rd_c0, rd_c1, ... (uniform ones are float literals inside the formulas)
 *   RD_REACTIONS          statements rd_r[m] = R_m(rd_u[0..], coefficients), one per morphogen:
 *                         the user's formulas translated by opencl/reaction_formula.cpp
 *   RD_HAS_FIXED          only when some vertices are Dirichlet (held) vertices
 *   RD_SHARED_WEIGHTS     only when every K_m is c_m K_0 (isotropic morphogens), with
 *   RD_WEIGHT_SCALES      {c_0, c_1, ...}: the explicit sub-step then reads morphogen 0's weights only
 *   RD_ELL_WIDTH          the explicit sub-step matrix's ELL slots per row
 *   RD_ZERO_ROW_SUMS      only when that matrix holds off-diagonal entries only (see RD_NEIGHBOUR)
 *   RD_FLOORS             {floor_0, floor_1, ...}: each morphogen's floor, -INFINITY for none
 *   RD_INTERLEAVED        only when the morphogens are stored vertex by vertex (see Layout)
 * so the kinetics are compiled code, not interpreted.
 *
 * Layout: every per-vertex array is padded to `stride` (the padded launch size) and morphogen m's
 * values are the block [m * stride, (m + 1) * stride) of one buffer; coefficient c's values are the
 * block c of `coefficients`. Every kernel runs on the padded size, hence the `i < n` guards on
 * writes (padding rows read valid, zero-weighted entries). With RD_INTERLEAVED (the explicit
 * integrator with five or more morphogens) the morphogens are stored vertex by vertex instead,
 * u[i * RD_MORPHOGENS + m]: a neighbour's five values are then one gather of 20 contiguous bytes
 * rather than five gathers from five blocks (a CPU's prefetchers follow a handful of streams, and
 * five blocks of neighbours made 15 of them). */
#include "device_types.h"

#ifndef RD_MORPHOGENS
#error "reaction_diffusion.cl needs the generated prelude (RD_MORPHOGENS, RD_REACTIONS, ...)"
#endif

/* The planted fault rd-swap-diffusion (opencl/planted_faults.hpp): morphogens 0 and 1 diffuse with
 * each other's stiffness. */
#ifdef PHYSARUM_FAULT_RD_SWAP_DIFFUSION
#define RD_STIFFNESS_OF(m) ((m) < 2 ? ((m) ^ 1) : (m))
#else
#define RD_STIFFNESS_OF(m) (m)
#endif

/* Where morphogen m's value at vertex i lies in a state buffer, and (RD_INDEX) vertex i's offset from
 * a morphogen's first value. */
#ifdef RD_INTERLEAVED
#define RD_AT(m, i) ((size_t)(i) * RD_MORPHOGENS + (size_t)(m))
#define RD_INDEX(i) ((size_t)(i) * RD_MORPHOGENS)
/* The host stores an interleaved run's ELL columns already multiplied by RD_MORPHOGENS (the offset of
 * the neighbour's first value): one multiplication per slot fewer in the sub-step's inner loop. */
#define RD_SLOT_INDEX(j) ((size_t)(j))
#else
#define RD_AT(m, i) ((size_t)(m) * stride + (size_t)(i))
#define RD_INDEX(i) (i)
#define RD_SLOT_INDEX(j) (j)
#endif

/* A neighbour's contribution to row i's diffusion sum of morphogen m. With RD_ZERO_ROW_SUMS the
 * matrix holds only the off-diagonal entries of rows that sum to zero (a diffusion operator leaves
 * constants alone, so W_ii = -sum_j W_ij), and (W u)_i = sum_j W_ij (u_j - u_i): one slot and one
 * gather fewer per row and morphogen than reading the diagonal as an entry, and no cancellation of
 * a large diagonal against its neighbours. A padding slot (value 0 at the row's own column) adds
 * 0 either way. The index is a signed int so that a CPU compiler gathers with 32-bit offsets. */
#ifdef RD_ZERO_ROW_SUMS
#define RD_NEIGHBOUR(m, j) (u_in[RD_AT(m, j)] - rd_u[m])
#else
#define RD_NEIGHBOUR(m, j) u_in[RD_AT(m, j)]
#endif

/* The morphogens of a vertex as one vector (rd_vector; a float3 for three, a float4 for four, a
 * float8 for five to eight):
 * RD_VECTOR_OF(a) from a private array, RD_VECTOR_TO(a, v) back into one, RD_GATHER(p, j) the values
 * at vertex j of the blocks p[0..]. */
#if RD_MORPHOGENS == 2
typedef float2 rd_vector;
#define RD_VECTOR_OF(a) ((float2)((a)[0], (a)[1]))
#define RD_GATHER(p, j) ((float2)((p)[0][j], (p)[1][j]))
#define RD_VECTOR_TO(a, v) ((a)[0] = (v).x, (a)[1] = (v).y)
#elif RD_MORPHOGENS == 3
typedef float3 rd_vector;
#define RD_VECTOR_OF(a) ((float3)((a)[0], (a)[1], (a)[2]))
#define RD_GATHER(p, j) ((float3)((p)[0][j], (p)[1][j], (p)[2][j]))
#define RD_VECTOR_TO(a, v) ((a)[0] = (v).x, (a)[1] = (v).y, (a)[2] = (v).z)
#elif RD_MORPHOGENS == 4
typedef float4 rd_vector;
#define RD_VECTOR_OF(a) ((float4)((a)[0], (a)[1], (a)[2], (a)[3]))
#define RD_GATHER(p, j) ((float4)((p)[0][j], (p)[1][j], (p)[2][j], (p)[3][j]))
#define RD_VECTOR_TO(a, v) ((a)[0] = (v).x, (a)[1] = (v).y, (a)[2] = (v).z, (a)[3] = (v).w)
#elif RD_MORPHOGENS <= 8
/* Five to eight (Meinhardt's stripe system has five): a float8 whose lanes past the last morphogen
 * repeat it (a gathered neighbour's lanes hold whatever follows it, see below). They are computed and
 * never kept: RD_VECTOR_TO writes the lanes from the last to the first, so each morphogen's own lane
 * is written last. */
typedef float8 rd_vector;
#define RD_LANE(k) ((k) < RD_MORPHOGENS ? (k) : RD_MORPHOGENS - 1)
#define RD_VECTOR_OF(a)                                                                              \
  ((float8)((a)[RD_LANE(0)], (a)[RD_LANE(1)], (a)[RD_LANE(2)], (a)[RD_LANE(3)], (a)[RD_LANE(4)], \
            (a)[RD_LANE(5)], (a)[RD_LANE(6)], (a)[RD_LANE(7)]))
#ifdef RD_INTERLEAVED
/* A vertex's values are contiguous: one load of eight floats from its first (vload8 needs only a
 * float's alignment). With fewer than eight morphogens the lanes past the last hold the next
 * vertex's first values, computed with and never kept (RD_VECTOR_TO); the host allocates the state
 * 8 - RD_MORPHOGENS floats longer so that the last vertex's load stays inside the buffer. One load
 * instead of a 16-byte load, a float and a shuffle: with the columns pre-multiplied, a slot is four
 * instructions on a CPU (bench/README.md, "Five morphogens in one load"). */
#define RD_GATHER(p, j) vload8(0, (p)[0] + (j))
#else
#define RD_GATHER(p, j)                                                                                      \
  ((float8)((p)[RD_LANE(0)][j], (p)[RD_LANE(1)][j], (p)[RD_LANE(2)][j], (p)[RD_LANE(3)][j], (p)[RD_LANE(4)][j], \
            (p)[RD_LANE(5)][j], (p)[RD_LANE(6)][j], (p)[RD_LANE(7)][j]))
#endif
#define RD_VECTOR_TO(a, v)                                                                          \
  ((a)[RD_LANE(7)] = (v).s7, (a)[RD_LANE(6)] = (v).s6, (a)[RD_LANE(5)] = (v).s5, (a)[4] = (v).s4, \
   (a)[3] = (v).s3, (a)[2] = (v).s2, (a)[1] = (v).s1, (a)[0] = (v).s0)
#else
#error "reaction_diffusion.cl: RD_MORPHOGENS is 2 to 8"
#endif

/* One forward Euler sub-step of every morphogen at row i:
 *   u_m' = u_m + (W_m u_m)_i + h R_m(u(i)),   W_m = -h diag(1/mass) K_m,
 * W_m assembled on the host in hybrid ELL + CSR form (opencl/hybrid_matrix.hpp), RD_ELL_WIDTH slots
 * wide (the host picks the width from the rows' lengths), with one column array shared by all
 * morphogens (their stiffness matrices share the Laplacian's pattern). Slot k of row i is the pair
 * column_weight[k * stride + i] = (column, bits of morphogen 0's weight); the other morphogens'
 * weights are blocks of `value`: value[((m - 1) * RD_ELL_WIDTH + k) * stride + i] (none when the
 * weights are shared). A column and its weight are read together, as one stream of 8-byte pairs
 * rather than two of 4 bytes: past the cache a CPU's prefetchers follow every stream the sub-step
 * reads, and with half as many slot streams the step ran 1.6x faster at 10^6 vertices on PoCL here
 * (bench/README.md; on an H200 it made no difference). One launch reads the columns once for all
 * morphogens, every morphogen's values once, u in and writes u out; the reaction costs no memory
 * traffic beyond the mapped coefficients.
 * Rows of held vertices have zero weights on the host and skip the reaction here, so they keep
 * their value exactly. rd_explicit_overflow then adds the entries of the few rows longer than the
 * ELL width. */
__kernel void rd_explicit_substep(const uint n, const uint stride, __global const int2* column_weight,
                                  __global const float* value, __global const float* coefficients,
                                  __global const uchar* fixed, const float h, __global const float* u_in,
                                  __global float* u_out) {
  const uint i = get_global_id(0);
  float rd_u[RD_MORPHOGENS], rd_r[RD_MORPHOGENS], diffusion[RD_MORPHOGENS];
  /* Slot k of row i is the pair at column_weight[k * stride + i]; each morphogen's values start at
   * their own pointer. Offsets in size_t and one pointer per block: the addresses are then a base
   * plus a scaled index, which a CPU compiler folds into its loads instead of computing 32-bit sums
   * per slot. */
  __global const int* slot_half = (__global const int*)(column_weight + i);
  __global const float* rd_in[RD_MORPHOGENS];
#pragma unroll
  for (uint m = 0; m < RD_MORPHOGENS; ++m) {
    rd_in[m] = u_in + RD_AT(m, 0);
    rd_u[m] = rd_in[m][RD_INDEX(i)];
  }
  /* All morphogens' neighbour values of a slot are one short vector, so a device that runs
   * work-items one at a time still does every morphogen's subtraction and multiply-add of a slot in
   * one instruction. PoCL runs this kernel so on x86 here: its loop vectoriser leaves a loop that
   * holds vector values (the pairs, this vector), and when it did vectorise across work-items (the
   * pairs read as one 64-bit integer) the neighbours' gathers made the step twice as slow (4.6
   * against 2.4 ms at 10^6 vertices). With this vector, the folded offsets and the weight read into
   * the multiply-add, the step went from 2.4 to 1.9 ms (bench/README.md, "One vector per slot"). A
   * GPU runs the vector's lanes one after another, as before.
   * The pair's halves are read as two ints rather than one int2: the weight then goes from memory
   * straight into the multiply-add instead of through an integer register and a shuffle. */
  const rd_vector own = RD_VECTOR_OF(rd_u);
  rd_vector sum = (rd_vector)(0.0f);
#ifdef RD_SHARED_WEIGHTS
  /* Every K_m is c_m K_0 (isotropic morphogens): one block of weights, each sum scaled by c_m. */
  const float rd_scale[RD_MORPHOGENS] = RD_WEIGHT_SCALES;
  (void)value;
#endif
#pragma unroll
  for (uint k = 0; k < RD_ELL_WIDTH; ++k) {
    const int j = slot_half[2 * (size_t)k * stride];
#ifdef RD_SHARED_WEIGHTS
    const float w = as_float(slot_half[2 * (size_t)k * stride + 1]);
#else
    /* Each morphogen's own weights (anisotropic diffusion), gathered into a vector of their own. */
    float rd_w[RD_MORPHOGENS];
#pragma unroll
    for (uint m = 0; m < RD_MORPHOGENS; ++m) {
      const uint s = RD_STIFFNESS_OF(m);
      rd_w[m] = s == 0 ? as_float(slot_half[2 * (size_t)k * stride + 1])
                       : value[((size_t)(s - 1) * RD_ELL_WIDTH + k) * stride + i];
    }
    const rd_vector w = RD_VECTOR_OF(rd_w);
#endif
    const rd_vector neighbour = RD_GATHER(rd_in, RD_SLOT_INDEX(j));
#ifdef RD_ZERO_ROW_SUMS
    sum += w * (neighbour - own);
#else
    sum += w * neighbour;
#endif
  }
  RD_VECTOR_TO(diffusion, sum);
#if defined(PHYSARUM_FAULT_RD_LANE_MIXUP) && RD_MORPHOGENS >= 5
  /* The planted fault rd-lane-mixup: the last morphogen takes the diffusion sum of the one before
   * it, a mix-up of the wide vector's lanes. */
  diffusion[RD_MORPHOGENS - 1] = diffusion[RD_MORPHOGENS - 2];
#endif
#ifdef RD_SHARED_WEIGHTS
#pragma unroll
  for (uint m = 0; m < RD_MORPHOGENS; ++m) diffusion[m] *= rd_scale[RD_STIFFNESS_OF(m)];
#endif
  RD_LOAD_COEFFICIENTS
  RD_REACTIONS
  (void)coefficients;
  if (i >= n) return;
#ifdef RD_HAS_FIXED
  if (fixed[i]) {
#pragma unroll
    for (uint m = 0; m < RD_MORPHOGENS; ++m) u_out[RD_AT(m, i)] = rd_u[m];
    return;
  }
#else
  (void)fixed;
#endif
#if defined(RD_INTERLEAVED)
  /* The update of every morphogen as one vector (the same operations, in the same order, as the
   * scalar form below), and the vertex's values are contiguous: the first four one 16-byte store. */
  const rd_vector updated = own + RD_VECTOR_OF(diffusion) + h * RD_VECTOR_OF(rd_r);
  float rd_new[RD_MORPHOGENS];
  RD_VECTOR_TO(rd_new, updated);
  vstore4(updated.lo, 0, u_out + RD_INDEX(i));
#pragma unroll
  for (uint m = 4; m < RD_MORPHOGENS; ++m) u_out[RD_AT(m, i)] = rd_new[m];
#else
#pragma unroll
  for (uint m = 0; m < RD_MORPHOGENS; ++m) u_out[RD_AT(m, i)] = rd_u[m] + diffusion[m] + h * rd_r[m];
#endif
}

/* The rest of the sub-step: each row with more than RD_ELL_WIDTH entries adds its remaining ones,
 * for every morphogen (CSR, one work-item per long row, so no two work-items touch one vertex).
 * Morphogen m's values are the block m of `value`, `entries` long. */
__kernel void rd_explicit_overflow(const uint count, const uint stride, const uint entries, __global const int* row,
                                   __global const int* row_start, __global const int* column,
                                   __global const float* value, __global const float* u_in, __global float* u_out) {
  const uint j = get_global_id(0);
  if (j >= count) return;
  const int i = row[j];
  const int end = row_start[j + 1];
#ifdef RD_SHARED_WEIGHTS
  const float rd_scale[RD_MORPHOGENS] = RD_WEIGHT_SCALES;
  (void)entries;
#endif
  float rd_u[RD_MORPHOGENS];
#pragma unroll
  for (uint m = 0; m < RD_MORPHOGENS; ++m) rd_u[m] = u_in[RD_AT(m, i)];
  (void)rd_u;  /* read by RD_NEIGHBOUR only with RD_ZERO_ROW_SUMS */
#pragma unroll
  for (uint m = 0; m < RD_MORPHOGENS; ++m) {
    float sum = 0.0f;
#ifdef RD_SHARED_WEIGHTS
    for (int e = row_start[j]; e < end; ++e) sum += value[e] * RD_NEIGHBOUR(m, column[e]);
    sum *= rd_scale[RD_STIFFNESS_OF(m)];
#else
    for (int e = row_start[j]; e < end; ++e)
      sum += value[RD_STIFFNESS_OF(m) * entries + e] * RD_NEIGHBOUR(m, column[e]);
#endif
    u_out[RD_AT(m, i)] += sum;
  }
}

/* The right-hand side of the IMEX step, (M + dt K_m) u_m' = M (u_m + dt R_m(u)) + c_m, for every
 * morphogen at row i. Held vertices get the row m_i u_m' = m_i u_m (the host put m_i on their
 * diagonal and removed their columns from the other rows, so the system stays symmetric), and c_m
 * (`coupling`, block m) is what those removed columns contributed: -dt sum_{j held} (K_m)_ij u_j,
 * constant while the held values are. */
__kernel void rd_imex_rhs(const uint n, const uint stride, __global const float* mass,
                          __global const float* coefficients, __global const uchar* fixed,
                          __global const float* coupling, const float dt, __global const float* u,
                          __global float* b) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  float rd_u[RD_MORPHOGENS], rd_r[RD_MORPHOGENS];
#pragma unroll
  for (uint m = 0; m < RD_MORPHOGENS; ++m) rd_u[m] = u[RD_AT(m, i)];
  RD_LOAD_COEFFICIENTS
  RD_REACTIONS
  (void)coefficients;
  const float m_i = mass[i];
#ifdef RD_HAS_FIXED
  if (fixed[i]) {
#pragma unroll
    for (uint m = 0; m < RD_MORPHOGENS; ++m) b[m * stride + i] = m_i * rd_u[m];
    return;
  }
#pragma unroll
  for (uint m = 0; m < RD_MORPHOGENS; ++m) b[m * stride + i] = m_i * (rd_u[m] + dt * rd_r[m]) + coupling[m * stride + i];
#else
  (void)fixed, (void)coupling;
#pragma unroll
  for (uint m = 0; m < RD_MORPHOGENS; ++m) b[m * stride + i] = m_i * (rd_u[m] + dt * rd_r[m]);
#endif
}

/* The floors (ReactionDiffusionSystem::minimum): a free vertex's value below its morphogen's floor is
 * raised to it, after the whole sub-step or implicit solve. A comparison, not fmax, so that a NaN
 * stays NaN (fmax would hide a diverging run), as in the reference. Launched only when some floor is
 * finite; held vertices keep their value. */
__kernel void rd_apply_floors(const uint n, const uint stride, __global const uchar* fixed, __global float* u) {
  const uint i = get_global_id(0);
  if (i >= n) return;
#ifdef RD_HAS_FIXED
  if (fixed[i]) return;
#else
  (void)fixed;
#endif
  const float floors[RD_MORPHOGENS] = RD_FLOORS;
  for (uint m = 0; m < RD_MORPHOGENS; ++m)
    if (u[RD_AT(m, i)] < floors[m]) u[RD_AT(m, i)] = floors[m];
}

/* One morphogen of an interleaved state copied out into a block of its own (`lane`), for what reads
 * a morphogen as one array: statistics, the host's reads. */
__kernel void rd_copy_morphogen(const uint n, const uint stride, const uint m, __global const float* u,
                                __global float* lane) {
  const uint i = get_global_id(0);
  (void)stride;  /* read by RD_AT only when blocks are stored one after another */
  if (i >= n) return;
  lane[i] = u[RD_AT(m, i)];
}
