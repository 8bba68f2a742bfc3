/* Movement (paper Sec. 3.2; mirrors reference/movement.cpp): each step an agent walks the geodesic
 * of length v dt along its heading, REFLECTING at boundaries, and deposits along the way (Eq. 4,
 * deposition.cl) when its deposit amount is not 0. The agents of one work-item move together, one
 * lane of one walker each (trace.cl), so their chains of face reads overlap.
 * Deposition is folded into the movement walk (the reference collects segments and deposits
 * afterwards): a kernel cannot keep a variable-length segment list, and depositing each piece as it
 * is walked is the same sum. */
#ifndef PHYSARUM_MOVEMENT_CL
#define PHYSARUM_MOVEMENT_CL
#include "deposition.cl"
#include "trace.cl"

/* BoundaryBehaviour::Terminate (Sec. 3.3): the walk stops at the boundary like a sensor's (depositing
 * only along what it walked, at the step's deposit per length) and the agent step respawns the
 * agent. Reflect otherwise. */
#ifdef PHYSARUM_BOUNDARY_TERMINATE
#define PHYSARUM_MOVE_REFLECT 0
#else
#define PHYSARUM_MOVE_REFLECT 1
#endif

/* Movement walks: PHYSARUM_MOVE_WALKERS walkers of `lanes` lanes (1..4) each, one agent a lane.
 * The walkers take turns step by step and each prefetches the faces it enters (walk_lanes_step),
 * so one walker's face reads are in flight while the others compute: a move crosses only a few
 * faces, and the four chains of one walker alone leave most of a face read's latency exposed. */
#if PHYSARUM_WALK_LANES > 1
#define PHYSARUM_MOVE_WALKERS PHYSARUM_VECTOR_MOVE_WALKERS
#else
#define PHYSARUM_MOVE_WALKERS 1
#endif

/* The movement walks of up to PHYSARUM_MOVE_WALKERS * lanes agents: lane i of walker h walks
 * length[h][i] from p[h][i] along unit d[h][i] in face[h][i], reflecting at boundaries; when
 * deposit_amount[h][i] != 0 each of its pieces deposits deposit_amount * (piece length / length)
 * at the piece's midpoint (the whole amount at the end point when the length is 0). Lanes whose
 * `active` is 0 do not walk. Ends in ends[h * lanes + i]. */
inline __attribute__((always_inline)) void trace_walk_lanes(
    __global const PhysarumFaceRecord* faces, const int lanes, const lane_int* face, const lane_float* px,
    const lane_float* py, const lane_float* dx, const lane_float* dy, const lane_float* length,
    const lane_float* deposit_amount, const lane_int* active, __global PhysarumDepositCell* deposits,
    const float deposit_scale, TraceEnd* ends PHYSARUM_SPECIES_CELL_OFFSETS_PARAMETER) {
  WalkLanes w[PHYSARUM_MOVE_WALKERS];
  lane_float per_length[PHYSARUM_MOVE_WALKERS];
#pragma unroll
  for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h) {
    w[h] = walk_lanes_start(faces, lanes, face[h], px[h], py[h], dx[h], dy[h], length[h], active[h]);
    per_length[h] = select((lane_float)(0.0f), deposit_amount[h] / w[h].remaining, w[h].remaining > 0.0f);
  }
  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS; ++step) {
    lane_int walking = (lane_int)(0);
#pragma unroll
    for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h) {
      if (LANE_ANY(w[h].walking)) {
        WalkPieces piece;
        walk_lanes_step(faces, lanes, &w[h], PHYSARUM_MOVE_REFLECT, &piece);
        deposit_pieces(faces, lanes, &piece, length[h], deposit_amount[h], per_length[h], deposits, deposit_scale
                       PHYSARUM_SPECIES_CELL_OFFSET(cell_offsets[h]));
      }
      walking |= w[h].walking;
    }
    if (!LANE_ANY(walking)) break;
  }
#pragma unroll
  for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h) walk_lane_ends(faces, &w[h], lanes, &ends[h * lanes]);
}

void move_agents(__global const PhysarumFaceRecord* faces, const int lanes, const lane_int* face,
                 const lane_float* px, const lane_float* py, const lane_float* dx, const lane_float* dy,
                 const lane_float* distance, const lane_float* deposit_amount, const lane_int* active,
                 __global PhysarumDepositCell* deposits, const float deposit_scale,
                 TraceEnd* ends PHYSARUM_SPECIES_CELL_OFFSETS_PARAMETER) {
#ifdef PHYSARUM_FAULT_DEPOSIT_ENDPOINT
  /* planted fault: the whole deposit at the end of the step instead of along the path */
  lane_float none[PHYSARUM_MOVE_WALKERS];
  for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h) none[h] = (lane_float)(0.0f);
  trace_walk_lanes(faces, lanes, face, px, py, dx, dy, distance, none, active, deposits, deposit_scale,
                   ends PHYSARUM_SPECIES_CELL_OFFSETS(cell_offsets));
  for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h)
    for (int lane = 0; lane < lanes; ++lane) {
      const float amount = float_in_lane(deposit_amount[h], lane);
      const TraceEnd* end = &ends[h * lanes + lane];
      if (int_in_lane(active[h], lane) && amount != 0.0f)
#ifdef PHYSARUM_SPECIES
        deposit_at_barycentric(faces, end->face, end->barycentric, amount,
                               deposits + int_in_lane(cell_offsets[h], lane), deposit_scale);
#else
        deposit_at_barycentric(faces, end->face, end->barycentric, amount, deposits, deposit_scale);
#endif
    }
#else
  trace_walk_lanes(faces, lanes, face, px, py, dx, dy, distance, deposit_amount, active, deposits, deposit_scale,
                   ends PHYSARUM_SPECIES_CELL_OFFSETS(cell_offsets));
#endif
}

#endif /* PHYSARUM_MOVEMENT_CL */
