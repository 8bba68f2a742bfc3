/* Movement (paper Sec. 3.2; mirrors reference/movement.cpp): each step an agent walks the geodesic
 * of length v dt along its heading, REFLECTING at boundaries, and deposits along the way (Eq. 4,
 * deposition.cl) when its deposit amount is not 0. The agents of one work-item move together, one
 * lane of one walker each (trace.cl), so their chains of face reads overlap. */
#ifndef PHYSARUM_MOVEMENT_CL
#define PHYSARUM_MOVEMENT_CL
#include "trace.cl"

void move_agents(__global const PhysarumFaceRecord* faces, const int lanes, const lane_int* face,
                 const lane_float* px, const lane_float* py, const lane_float* dx, const lane_float* dy,
                 const lane_float* distance, const lane_float* deposit_amount, const lane_int* active,
                 __global PhysarumDepositCell* deposits, const float deposit_scale, TraceEnd* ends) {
#ifdef PHYSARUM_FAULT_DEPOSIT_ENDPOINT
  /* planted fault: the whole deposit at the end of the step instead of along the path */
  lane_float none[PHYSARUM_MOVE_WALKERS];
  for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h) none[h] = (lane_float)(0.0f);
  trace_walk_lanes(faces, lanes, face, px, py, dx, dy, distance, none, active, deposits, deposit_scale, ends);
  for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h)
    for (int lane = 0; lane < lanes; ++lane) {
      const float amount = float_in_lane(deposit_amount[h], lane);
      const TraceEnd* end = &ends[h * lanes + lane];
      if (int_in_lane(active[h], lane) && amount != 0.0f)
        deposit_at_barycentric(faces, end->face, end->barycentric, amount, deposits, deposit_scale);
    }
#else
  trace_walk_lanes(faces, lanes, face, px, py, dx, dy, distance, deposit_amount, active, deposits, deposit_scale,
                   ends);
#endif
}

#endif /* PHYSARUM_MOVEMENT_CL */
