/* Movement (paper Sec. 3.2; mirrors reference/movement.cpp): each step an agent walks the geodesic
 * of length v dt along its heading, REFLECTING at boundaries, and deposits along the way (Eq. 4,
 * deposition.cl) when deposit_amount is not 0. */
#ifndef PHYSARUM_MOVEMENT_CL
#define PHYSARUM_MOVEMENT_CL
#include "trace.cl"

TraceEnd move_agent(__global const PhysarumFaceRecord* faces, const int face, const float2 position,
                    const float2 heading, const float distance, const float deposit_amount,
                    __global PhysarumDepositCell* deposits, const float deposit_scale) {
#ifdef PHYSARUM_FAULT_DEPOSIT_ENDPOINT
  /* planted fault: the whole deposit at the end of the step instead of along the path */
  const TraceEnd end = trace_walk(faces, face, position, heading, distance, 0.0f, 0, deposit_scale);
  if (deposit_amount != 0.0f) deposit_at_barycentric(faces, end.face, end.barycentric, deposit_amount, deposits, deposit_scale);
  return end;
#else
  return trace_walk(faces, face, position, heading, distance, deposit_amount, deposits, deposit_scale);
#endif
}

#endif /* PHYSARUM_MOVEMENT_CL */
