/* Straight-line (geodesic) walking across intrinsic faces, in float32: the device twin of
 * common/trace.cpp, step for step (same exit rule, same exit-point construction, same reflection),
 * so a reader can compare them side by side. Differences are only those float32 forces: the
 * parallel tolerance is relative to float rounding, and end points are clamped into the end face.
 *
 * Cost: a walk is a chain of dependent face reads, so each step does as little as it can.
 *   - Walks advance as four lanes of float4 vectors (WalkLanes): the three sensors of an agent walk
 *     in lockstep, one lane each, so one vector instruction does the arithmetic of all three and the
 *     processor overlaps three independent chains of face reads instead of waiting on one. A lane's
 *     choices (which edge, cross or end, reflect or stop) are selects, not branches: the exit edge
 *     is as good as random, and a mispredicted branch costs as much as the arithmetic it skips.
 *   - The point's barycentric coordinates are carried along rather than solved for: after a
 *     crossing the point lies on the shared edge, where they are (1 - s, s, 0) up to the corner
 *     order; only their rate along the heading needs the new face's layout, and the face record
 *     stores that layout as reciprocals (device_types.h), so it costs multiplications only.
 * Deposition is folded into the movement walk (the reference collects segments and deposits
 * afterwards): a kernel cannot keep a variable-length segment list, and depositing each piece as it
 * is walked is the same sum. */
#ifndef PHYSARUM_TRACE_CL
#define PHYSARUM_TRACE_CL
#include "device_types.h"
#include "agents.cl"
#include "deposition.cl"

/* Per-lane reads of one face-record field (each lane its own face, and its own edge e). With
 * lanes == 1 (a compile-time constant where the walk is inlined) only lane 0's face is read, so a
 * lone walk pays for one read, not four. */
#define GATHER_FIELD(type4, faces, f, field, lanes)                                                    \
  ((lanes) == 1 ? (type4)((faces)[(f).x].field)                                                        \
                : (type4)((faces)[(f).x].field, (faces)[(f).y].field, (faces)[(f).z].field, (faces)[(f).w].field))
#define GATHER_EDGE_FIELD(type4, faces, f, e, field, lanes)                                          \
  ((lanes) == 1 ? (type4)((faces)[(f).x].field[(e).x])                                               \
                : (type4)((faces)[(f).x].field[(e).x], (faces)[(f).y].field[(e).y],                  \
                          (faces)[(f).z].field[(e).z], (faces)[(f).w].field[(e).w]))

/* Per lane, component k (0, 1 or 2) of a three-component quantity held as three vectors. */
float4 pick3(const int4 k, const float4 v0, const float4 v1, const float4 v2) {
  return select(select(v2, v1, k == 1), v0, k == 0);
}

/* (k + 1) % 3 and (k + 2) % 3 per lane, for k in 0..2. */
int4 next3(const int4 k) { return select(k + 1, (int4)(0), k == 2); }
int4 previous3(const int4 k) { return select(k - 1, (int4)(2), k == 0); }

/* Barycentric coordinates (three vectors) of the point a fraction s along edge e (corner e to
 * corner e+1). */
void edge_point_lanes(const int4 e, const float4 s, float4* b0, float4* b1, float4* b2) {
  const int4 e_next = next3(e);
  const float4 zero = (float4)(0.0f);
  *b0 = select(select(zero, s, e_next == 0), 1.0f - s, e == 0);
  *b1 = select(select(zero, s, e_next == 1), 1.0f - s, e == 1);
  *b2 = select(select(zero, s, e_next == 2), 1.0f - s, e == 2);
}

/* Coordinates that rounding left marginally outside the face, clamped at zero and renormalised:
 * every walk ends inside its end face (the centroid when nothing usable is left). */
void clamp_barycentric_lanes(float4* b0, float4* b1, float4* b2) {
  const int4 inside = (*b0 >= 0.0f) & (*b1 >= 0.0f) & (*b2 >= 0.0f) & isfinite(*b0 + *b1 + *b2);
  const float4 zero = (float4)(0.0f);
  const float4 c0 = select(zero, fmax(*b0, zero), isfinite(*b0));
  const float4 c1 = select(zero, fmax(*b1, zero), isfinite(*b1));
  const float4 c2 = select(zero, fmax(*b2, zero), isfinite(*b2));
  const float4 sum = c0 + c1 + c2;
  const int4 usable = sum > 0.0f;
  const float4 third = (float4)(1.0f / 3.0f);
  *b0 = select(select(third, c0 / sum, usable), *b0, inside);
  *b1 = select(select(third, c1 / sum, usable), *b1, inside);
  *b2 = select(select(third, c2 / sum, usable), *b2, inside);
}

/* Directions within this relative tolerance of parallel to an edge do not cross it. The
 * reference uses 1e-12 in double; this is the same rule a few float ulps wide. */
#define PHYSARUM_PARALLEL_TOLERANCE 1e-6f

/* Up to four walks in progress, one per lane. Masks are vector-comparison values: -1 true, 0 false.
 * A lane that is not walking keeps its state; its face stays a valid index, so reads for it are
 * harmless. */
typedef struct {
  int4 face;
  float4 b0, b1, b2;  /* barycentric coordinates of the current point in `face` */
  float4 dx, dy;      /* unit heading in `face`'s frame */
  float4 remaining;   /* length still to walk */
  int4 entry_edge;    /* the edge just entered through (or reflected off): never an exit at t = 0 */
  int4 walking;       /* the lane has length left and has not stopped */
  int4 hit_boundary;  /* the lane met a boundary (and, for sensors, stopped there) */
  int4 face_crossings;
} WalkLanes;

/* The piece each walking lane walked in one step: from start to end (barycentric, in `face`). */
typedef struct {
  int4 face;
  float4 start0, start1, start2;
  float4 end0, end1, end2;
  float4 length;
  int4 walked; /* the lane was walking at the start of the step */
} WalkPieces;

/* Lanes where `active` is set (`lanes` of them, the first ones) start walking `length` from p (in `face`) along unit d. */
inline __attribute__((always_inline)) WalkLanes walk_lanes_start(
    __global const PhysarumFaceRecord* faces, const int lanes, const int4 face, const float4 px, const float4 py,
    const float4 dx, const float4 dy, const float4 length, const int4 active) {
  WalkLanes w;
  w.face = face;
  w.b2 = py * GATHER_FIELD(float4, faces, face, inv_y2, lanes);
  w.b1 = px * GATHER_FIELD(float4, faces, face, inv_x1, lanes) - py * GATHER_FIELD(float4, faces, face, shear, lanes);
  w.b0 = 1.0f - w.b1 - w.b2;
  w.dx = dx;
  w.dy = dy;
  w.remaining = select((float4)(0.0f), length, active & (length > 0.0f) & isfinite(length));
  w.entry_edge = (int4)(-1);
  w.walking = active;
  w.hit_boundary = (int4)(0);
  w.face_crossings = (int4)(0);
  return w;
}

/* One piece of every walking lane: the lane either ends (its whole length walked), stops at a
 * boundary (sensors: reflect == 0), reflects (agents) or crosses into the neighbour.
 * Inlined on purpose: the walker must live in registers, not behind a pointer (the attribute is a
 * hint every clang-based OpenCL compiler honours). */
inline __attribute__((always_inline)) void walk_lanes_step(__global const PhysarumFaceRecord* faces,
                                                           const int lanes, WalkLanes* w, const int reflect,
                                                           WalkPieces* piece) {
  const int4 f = w->face;
  const float4 b0 = w->b0, b1 = w->b1, b2 = w->b2, dx = w->dx, dy = w->dy;
  const float4 inv_x1 = GATHER_FIELD(float4, faces, f, inv_x1, lanes);
  const float4 shear = GATHER_FIELD(float4, faces, f, shear, lanes);
  const float4 inv_y2 = GATHER_FIELD(float4, faces, f, inv_y2, lanes);
  const float4 db2 = dy * inv_y2;
  const float4 db1 = dx * inv_x1 - dy * shear;
  const float4 db0 = -db1 - db2;
  const float4 parallel = -PHYSARUM_PARALLEL_TOLERANCE * (fabs(db0) + fabs(db1) + fabs(db2));

  /* Leave where a decreasing coordinate reaches zero first; coordinate k vanishes on edge
   * (k+1)%3, which must not be the edge just entered through. Ties keep the lower k. */
  const int4 e_in = w->entry_edge;
  const float4 n0 = fmax(b0, 0.0f), n1 = fmax(b1, 0.0f), n2 = fmax(b2, 0.0f);
  const float4 never = (float4)(INFINITY);
  const int4 exits0 = (e_in != 1) & (db0 < parallel);
  const int4 exits1 = (e_in != 2) & (db1 < parallel);
  const int4 exits2 = (e_in != 0) & (db2 < parallel);
  const float4 t0 = select(never, n0 / -db0, exits0);
  const float4 t1 = select(never, n1 / -db1, exits1);
  const float4 t2 = select(never, n2 / -db2, exits2);
  int4 corner = select(select((int4)(2), (int4)(1), t1 <= t2), (int4)(0), (t0 <= t1) & (t0 <= t2));
  float4 t_exit = fmin(t0, fmin(t1, t2));
  /* Only the entry edge lies ahead: rounding made a heading parallel to it look like it points
   * back. Crossing back is still a valid move (the step bound caps any ping-pong). */
  const int4 back_corner = previous3(e_in);
  const float4 back_rate = pick3(back_corner, db0, db1, db2);
  const int4 back = ~(exits0 | exits1 | exits2) & (e_in >= 0) & (back_rate < 0.0f);
  corner = select(corner, back_corner, back);
  t_exit = select(t_exit, pick3(back_corner, n0, n1, n2) / -back_rate, back);

  const int4 crossing = w->walking & (exits0 | exits1 | exits2 | back) & (t_exit < w->remaining);
  const int4 ending = w->walking & ~crossing;

  /* Ending lanes walk what remains inside this face. */
  float4 end0 = b0 + w->remaining * db0, end1 = b1 + w->remaining * db1, end2 = b2 + w->remaining * db2;
  clamp_barycentric_lanes(&end0, &end1, &end2);

  /* Crossing lanes: the exit point on edge e, as a fraction s along it, from the two surviving
   * coordinates: exactly on the edge whatever rounding did to the point. */
  const int4 e = next3(corner);
  const int4 e_next = next3(e);
  const float4 at0 = b0 + t_exit * db0, at1 = b1 + t_exit * db1, at2 = b2 + t_exit * db2;
  const float4 weight_from = fmax(pick3(e, at0, at1, at2), 0.0f);
  const float4 weight_to = fmax(pick3(e_next, at0, at1, at2), 0.0f);
  const float4 total = weight_from + weight_to;
  const float4 s = select((float4)(0.5f), clamp(weight_to / total, 0.0f, 1.0f), total > 0.0f);
  float4 exit0, exit1, exit2;
  edge_point_lanes(e, s, &exit0, &exit1, &exit2);

  piece->face = f;
  piece->start0 = b0, piece->start1 = b1, piece->start2 = b2;
  piece->end0 = select(exit0, end0, ending);
  piece->end1 = select(exit1, end1, ending);
  piece->end2 = select(exit2, end2, ending);
  piece->length = select(t_exit, w->remaining, ending);
  piece->walked = w->walking;

  w->b0 = select(b0, piece->end0, w->walking);
  w->b1 = select(b1, piece->end1, w->walking);
  w->b2 = select(b2, piece->end2, w->walking);
  w->remaining = select(select(w->remaining, w->remaining - t_exit, crossing), (float4)(0.0f), ending);
  w->walking &= ~ending;
  if (!any(crossing)) return;

  const int4 g = GATHER_EDGE_FIELD(int4, faces, f, e, neighbour, lanes);
  const int4 boundary = crossing & (g < 0);
  const int4 through = crossing & (g >= 0);
  w->hit_boundary |= boundary;
#ifdef PHYSARUM_FAULT_NO_REFLECT
  /* planted fault: agents stop at the boundary instead of reflecting */
  w->walking &= ~boundary;
#else
  if (!reflect) w->walking &= ~boundary;
  else if (any(boundary)) {
    /* Mirror the heading about the edge line and walk on inside the same face. Edge e runs from
     * corner e to corner e+1: corner 0 = (0, 0), corner 1 = (x1, 0), corner 2 = (x2, y2). */
    const float4 x1 = 1.0f / inv_x1, y2 = 1.0f / inv_y2, x2 = shear * x1 * y2;
    const float4 edge_x = select(select(-x2, x2 - x1, e == 1), x1, e == 0);
    const float4 edge_y = select(select(-y2, y2, e == 1), (float4)(0.0f), e == 0);
    const float4 edge_length = sqrt(edge_x * edge_x + edge_y * edge_y);
    const float4 ux = edge_x / edge_length, uy = edge_y / edge_length;
    const float4 along = 2.0f * (dx * ux + dy * uy);
    const float4 rx = along * ux - dx, ry = along * uy - dy;
    const float4 r_length = sqrt(rx * rx + ry * ry);
    w->dx = select(w->dx, rx / r_length, boundary);
    w->dy = select(w->dy, ry / r_length, boundary);
    w->entry_edge = select(w->entry_edge, e, boundary);
  }
#endif
  if (!any(through)) return;

  /* Cross into g, where the shared edge runs from corner j+1 to corner j. */
  const int4 edges_of = convert_int4(GATHER_FIELD(uint4, faces, f, neighbour_edges, lanes) >> convert_uint4(2 * e));
  const int4 j = edges_of & 3;
  const float4 c = GATHER_EDGE_FIELD(float4, faces, f, e, transition_cos, lanes);
  const float4 sn = GATHER_EDGE_FIELD(float4, faces, f, e, transition_sin, lanes);
  float4 next0, next1, next2;
  edge_point_lanes(j, 1.0f - s, &next0, &next1, &next2);
  w->dx = select(w->dx, c * dx - sn * dy, through);
  w->dy = select(w->dy, sn * dx + c * dy, through);
  w->b0 = select(w->b0, next0, through);
  w->b1 = select(w->b1, next1, through);
  w->b2 = select(w->b2, next2, through);
  w->face = select(w->face, g, through);
  w->entry_edge = select(w->entry_edge, j, through);
  w->face_crossings -= through; /* through is -1 where a lane crossed */
}

typedef struct {
  int face;
  float2 position;
  float3 barycentric; /* of position */
  float2 heading;
  int hit_boundary;
  int face_crossings;
} TraceEnd;

float lane_float(const float4 v, const int lane) {
  return lane == 0 ? v.x : (lane == 1 ? v.y : (lane == 2 ? v.z : v.w));
}
int lane_int(const int4 v, const int lane) { return lane == 0 ? v.x : (lane == 1 ? v.y : (lane == 2 ? v.z : v.w)); }

/* Where lane `lane` of a walk ended (a lane the step bound cut short is clamped into its face). */
TraceEnd walk_lane_end(__global const PhysarumFaceRecord* faces, const WalkLanes* w, const int lane) {
  float4 b0 = w->b0, b1 = w->b1, b2 = w->b2;
  clamp_barycentric_lanes(&b0, &b1, &b2);
  TraceEnd r;
  r.face = lane_int(w->face, lane);
  r.barycentric = (float3)(lane_float(b0, lane), lane_float(b1, lane), lane_float(b2, lane));
  r.position = r.barycentric.y * face_corner1(faces, r.face) + r.barycentric.z * face_corner2(faces, r.face);
  r.heading = (float2)(lane_float(w->dx, lane), lane_float(w->dy, lane));
  r.hit_boundary = lane_int(w->hit_boundary, lane) != 0;
  r.face_crossings = lane_int(w->face_crossings, lane);
  return r;
}

/* Sets lane `lane` of v to x (lane a compile-time constant where this is inlined). */
float4 with_lane(const float4 v, const int lane, const float x) {
  return select(v, (float4)(x), (int4)(0, 1, 2, 3) == lane);
}
int4 with_lane_int(const int4 v, const int lane, const int x) {
  return select(v, (int4)(x), (int4)(0, 1, 2, 3) == lane);
}

/* The movement walks of `lanes` agents (1..4) in lockstep, one lane each: lane i walks length[i]
 * from p[i] along unit d[i] in face[i], reflecting at boundaries; when deposit_amount[i] != 0 each
 * of its pieces deposits deposit_amount[i] * (piece length / length[i]) at the piece's midpoint
 * (the whole amount at the end point when the length is 0). Lanes whose `active` is 0 do not walk. */
void trace_walk_lanes(__global const PhysarumFaceRecord* faces, const int lanes, const int4 face, const float4 px,
                      const float4 py, const float4 dx, const float4 dy, const float4 length,
                      const float4 deposit_amount, const int4 active, __global PhysarumDepositCell* deposits,
                      const float deposit_scale, TraceEnd* ends) {
  WalkLanes w = walk_lanes_start(faces, lanes, face, px, py, dx, dy, length, active);
  const float4 per_length = select((float4)(0.0f), deposit_amount / w.remaining, w.remaining > 0.0f);
  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS && any(w.walking); ++step) {
    WalkPieces piece;
    walk_lanes_step(faces, lanes, &w, 1, &piece);
    for (int lane = 0; lane < lanes; ++lane) {
      const float amount = lane_float(deposit_amount, lane);
      if (!lane_int(piece.walked, lane) || amount == 0.0f) continue;
      const int piece_face = lane_int(piece.face, lane);
      const float3 start = (float3)(lane_float(piece.start0, lane), lane_float(piece.start1, lane),
                                    lane_float(piece.start2, lane));
      const float3 end = (float3)(lane_float(piece.end0, lane), lane_float(piece.end1, lane),
                                  lane_float(piece.end2, lane));
      const float piece_length = lane_float(piece.length, lane);
      if (!(lane_float(length, lane) > 0.0f))
        deposit_at_barycentric(faces, piece_face, end, amount, deposits, deposit_scale);
      else if (piece_length > 0.0f)
        deposit_at_barycentric(faces, piece_face, 0.5f * (start + end), lane_float(per_length, lane) * piece_length,
                               deposits, deposit_scale);
    }
  }
  for (int lane = 0; lane < lanes; ++lane) ends[lane] = walk_lane_end(faces, &w, lane);
}

/* The three sensor walks of one agent (left, centre, right), which stop at boundaries, in lanes
 * 0..2 of one lockstep walk. Results in the order of the directions. */
void trace_three_sensors(__global const PhysarumFaceRecord* faces, const int face, const float2 p, const float2 d0,
                         const float2 d1, const float2 d2, const float length, TraceEnd* end0, TraceEnd* end1,
                         TraceEnd* end2) {
  WalkLanes w = walk_lanes_start(faces, 3, (int4)(face), (float4)(p.x), (float4)(p.y), (float4)(d0.x, d1.x, d2.x, 0.0f),
                                 (float4)(d0.y, d1.y, d2.y, 0.0f), (float4)(length), (int4)(-1, -1, -1, 0));
  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS && any(w.walking); ++step) {
    WalkPieces piece;
    walk_lanes_step(faces, 3, &w, 0, &piece);
  }
  *end0 = walk_lane_end(faces, &w, 0);
  *end1 = walk_lane_end(faces, &w, 1);
  *end2 = walk_lane_end(faces, &w, 2);
}

#endif /* PHYSARUM_TRACE_CL */
