/* Deposition along the path (paper Eq. 4; mirrors reference/deposition.cpp). Each per-face piece of
 * a step deposits its share of r_dep dt at its midpoint, split over the face's corners by the
 * midpoint's barycentric weights, into an AMOUNT per vertex; pheromone_add_deposits (diffusion_decay.cl)
 * then divides by the vertex mass and adds it to the field.
 *
 * Order independence: amounts accumulate as 64-bit fixed point (round(amount * scale), scale a power
 * of two chosen by the host so the largest possible per-vertex sum of one step cannot overflow), and
 * integer addition is associative, so the sum does not depend on which work-item adds first: a run is
 * deterministic on a given device. Devices without cl_khr_int64_base_atomics are built with
 * PHYSARUM_FLOAT_DEPOSITS and add floats by compare-and-swap instead (correct, not bit-reproducible). */
#ifndef PHYSARUM_DEPOSITION_CL
#define PHYSARUM_DEPOSITION_CL
#include "device_types.h"
#include "trace.cl"

#include "deposit_cells.h"
#include "species.cl"

/* Bounded retries of the float compare-and-swap: contention on one vertex cannot reach this many
 * collisions in practice; giving up after it loses one deposit rather than hanging the device. */
#define PHYSARUM_MAX_CAS_ATTEMPTS 4096

/* x rounded to the nearest integer, ties to even: rint(x) in two additions. Floats of magnitude
 * 2^23 and more are integers already; below it, x + 2^23 (with x's sign) lies where the float
 * spacing is exactly 1, so float addition's own round-to-nearest-even rounds it, and subtracting
 * 2^23 again is exact. (PoCL expands rint and convert_long_rte into compares and branches, and
 * deposits round several times per agent-step.) */
float nearest_integer(const float x) {
  const float magic = copysign(0x1p23f, x);
  return fabs(x) < 0x1p23f ? (x + magic) - magic : x;
}

void deposit_amount(__global PhysarumDepositCell* cell, const float amount, const float scale) {
#ifdef PHYSARUM_FLOAT_DEPOSITS
  (void)scale;
  volatile __global uint* word = (volatile __global uint*)cell;
  for (int attempt = 0; attempt < PHYSARUM_MAX_CAS_ATTEMPTS; ++attempt) {
    const uint expected = *word;
    const uint desired = as_uint(as_float(expected) + amount);
    if (atomic_cmpxchg(word, expected, desired) == expected) return;
  }
#else
  const long units = convert_long(nearest_integer(amount * scale));
  if (units != 0) atom_add((volatile __global long*)cell, units);
#endif
}

/* The fraction of the step [age, age + dt] during which the agent is active (age >= t_a). */
float active_fraction(const float age, const float dt, const float activation_time) {
  if (dt <= 0.0f) return age >= activation_time ? 1.0f : 0.0f;
  return clamp((age + dt - activation_time) / dt, 0.0f, 1.0f);
}

/* Splits `amount` over the corners of `face` by the barycentric weights b of the deposit point. */
void deposit_at_barycentric(__global const PhysarumFaceRecord* faces, const int face, const float3 b,
                            const float amount, __global PhysarumDepositCell* deposits, const float scale) {
  deposit_amount(&deposits[faces[face].vertex[0]], amount * b.x, scale);
  deposit_amount(&deposits[faces[face].vertex[1]], amount * b.y, scale);
  deposit_amount(&deposits[faces[face].vertex[2]], amount * b.z, scale);
}

/* The deposits of one step's pieces (see trace_walk_lanes): each lane's amount and point as lane
 * vectors, one instruction for all lanes; the deposits themselves lane by lane. */
void deposit_pieces(__global const PhysarumFaceRecord* faces, const int lanes, const WalkPieces* piece,
                    const lane_float length, const lane_float walk_amount, const lane_float per_length,
                    __global PhysarumDepositCell* deposits, const float deposit_scale PHYSARUM_SPECIES_CELL_OFFSET_PARAMETER) {
  /* Lane i deposits walk_amount[i] spread over its walk; a walk of no length all of it at its end
   * point. */
  const lane_int whole = !(length > 0.0f);
  const lane_float amount = select(per_length * piece->length, walk_amount, whole);
  const lane_float at0 = select(0.5f * (piece->start0 + piece->end0), piece->end0, whole);
  const lane_float at1 = select(0.5f * (piece->start1 + piece->end1), piece->end1, whole);
  const lane_float at2 = select(0.5f * (piece->start2 + piece->end2), piece->end2, whole);
  const lane_int depositing = piece->walked & (walk_amount != 0.0f) & (whole | (piece->length > 0.0f));
  for (int lane = 0; lane < lanes; ++lane)
    if (int_in_lane(depositing, lane))
      deposit_at_barycentric(faces, int_in_lane(piece->face, lane),
                             (float3)(float_in_lane(at0, lane), float_in_lane(at1, lane), float_in_lane(at2, lane)),
#ifdef PHYSARUM_SPECIES
                             float_in_lane(amount, lane), deposits + int_in_lane(cell_offset, lane), deposit_scale);
#else
                             float_in_lane(amount, lane), deposits, deposit_scale);
#endif
}

#endif /* PHYSARUM_DEPOSITION_CL */
