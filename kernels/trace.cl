/* Straight-line (geodesic) walking across intrinsic faces, in float32: the device twin of
 * common/surface/trace.cpp, step for step (same exit rule, same exit-point construction, same reflection),
 * so a reader can compare them side by side. Differences are only those float32 forces: the
 * parallel tolerance is relative to float rounding, and end points are clamped into the end face.
 *
 * Cost: a walk is a chain of dependent face reads, so each step does as little as it can.
 *   - Several walks advance in lockstep (WalkLanes), so the processor overlaps independent chains of
 *     face reads instead of waiting on one: the three sensors of an agent, and the moves of the
 *     agents of one work-item. On CPUs they are the lanes of float4 vectors, so one instruction
 *     does the arithmetic of all of them (PHYSARUM_WALK_LANES, below). A lane's choices (which
 *     edge, cross or end, reflect or stop) are selects, not branches: the exit edge is as good as
 *     random, and a mispredicted branch costs as much as the arithmetic it skips.
 *   - The point's barycentric coordinates are carried along rather than solved for: after a
 *     crossing the point lies on the shared edge, where they are (1 - s, s, 0) up to the corner
 *     order; only their rate along the heading needs the new face's layout, and the face record
 *     stores that layout as reciprocals (device_types.h), so it costs multiplications only.
 * The lane layer (vector or scalar lanes) is lanes.h; the movement walks, which deposit as they go,
 * are movement.cl, their deposits deposition.cl. */
#ifndef PHYSARUM_TRACE_CL
#define PHYSARUM_TRACE_CL
#include "device_types.h"
#include "agents.cl"
#include "lanes.h"

/* Barycentric coordinates (three vectors) of the point a fraction s along edge e (corner e to
 * corner e+1). */
void edge_point_lanes(const lane_int e, const lane_float s, lane_float* b0, lane_float* b1, lane_float* b2) {
  const lane_int e_next = next3(e);
  const lane_float zero = (lane_float)(0.0f);
  *b0 = select(select(zero, s, e_next == 0), 1.0f - s, e == 0);
  *b1 = select(select(zero, s, e_next == 1), 1.0f - s, e == 1);
  *b2 = select(select(zero, s, e_next == 2), 1.0f - s, e == 2);
}

/* Coordinates that rounding left marginally outside the face, clamped at zero and renormalised:
 * every walk ends inside its end face (the centroid when nothing usable is left). */
void clamp_barycentric_lanes(lane_float* b0, lane_float* b1, lane_float* b2) {
  const lane_int inside = (*b0 >= 0.0f) & (*b1 >= 0.0f) & (*b2 >= 0.0f) & isfinite(*b0 + *b1 + *b2);
  const lane_float zero = (lane_float)(0.0f);
  const lane_float c0 = select(zero, fmax(*b0, zero), isfinite(*b0));
  const lane_float c1 = select(zero, fmax(*b1, zero), isfinite(*b1));
  const lane_float c2 = select(zero, fmax(*b2, zero), isfinite(*b2));
  const lane_float sum = c0 + c1 + c2;
  const lane_int usable = sum > 0.0f;
  const lane_float third = (lane_float)(1.0f / 3.0f);
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
  lane_int face;
  lane_float b0, b1, b2;  /* barycentric coordinates of the current point in `face` */
  lane_float dx, dy;      /* unit heading in `face`'s frame */
  lane_float remaining;   /* length still to walk */
  lane_int entry_edge;    /* the edge just entered through (or reflected off): never an exit at t = 0 */
  lane_int walking;       /* the lane has length left and has not stopped */
  lane_int hit_boundary;  /* the lane met a boundary (and, for sensors, stopped there) */
  lane_int face_crossings;
} WalkLanes;

/* The piece each walking lane walked in one step: from start to end (barycentric, in `face`). */
typedef struct {
  lane_int face;
  lane_float start0, start1, start2;
  lane_float end0, end1, end2;
  lane_float length;
  lane_int walked; /* the lane was walking at the start of the step */
} WalkPieces;

/* Lanes where `active` is set (among the first `lanes`) start walking `length` from p (in `face`)
 * along unit d. */
WalkLanes walk_lanes_start(__global const PhysarumFaceRecord* faces, const int lanes, const lane_int face,
                           const lane_float px, const lane_float py, const lane_float dx, const lane_float dy,
                           const lane_float length, const lane_int active) {
  WalkLanes w;
  w.face = face;
  w.b2 = py * GATHER_FIELD(lane_float, faces, face, inv_y2, lanes);
  w.b1 = px * GATHER_FIELD(lane_float, faces, face, inv_x1, lanes) -
         py * GATHER_FIELD(lane_float, faces, face, shear, lanes);
  w.b0 = 1.0f - w.b1 - w.b2;
  w.dx = dx;
  w.dy = dy;
  w.remaining = select((lane_float)(0.0f), length, active & (length > 0.0f) & isfinite(length));
  w.entry_edge = (lane_int)(-1);
  w.walking = active;
  w.hit_boundary = (lane_int)(0);
  w.face_crossings = (lane_int)(0);
  return w;
}

/* One piece of every walking lane: the lane either ends (its whole length walked), stops at a
 * boundary (sensors: reflect == 0), reflects (agents) or crosses into the neighbour.
 * Inlined on purpose: the walker must live in registers, not behind a pointer (the attribute is a
 * hint every clang-based OpenCL compiler honours). */
inline __attribute__((always_inline)) void walk_lanes_step(__global const PhysarumFaceRecord* faces,
                                                           const int lanes, WalkLanes* w, const int reflect,
                                                           WalkPieces* piece) {
  const lane_int f = w->face;
  const lane_float b0 = w->b0, b1 = w->b1, b2 = w->b2, dx = w->dx, dy = w->dy;
  const lane_float inv_x1 = GATHER_FIELD(lane_float, faces, f, inv_x1, lanes);
  const lane_float shear = GATHER_FIELD(lane_float, faces, f, shear, lanes);
  const lane_float inv_y2 = GATHER_FIELD(lane_float, faces, f, inv_y2, lanes);
  const lane_float db2 = dy * inv_y2;
  const lane_float db1 = dx * inv_x1 - dy * shear;
  const lane_float db0 = -db1 - db2;
  const lane_float parallel = -PHYSARUM_PARALLEL_TOLERANCE * (fabs(db0) + fabs(db1) + fabs(db2));

  /* Leave where a decreasing coordinate reaches zero first; coordinate k vanishes on edge
   * (k+1)%3, which must not be the edge just entered through. Ties keep the lower k. */
  const lane_int e_in = w->entry_edge;
  const lane_float n0 = fmax(b0, 0.0f), n1 = fmax(b1, 0.0f), n2 = fmax(b2, 0.0f);
  const lane_float never = (lane_float)(INFINITY);
  const lane_int exits0 = (e_in != 1) & (db0 < parallel);
  const lane_int exits1 = (e_in != 2) & (db1 < parallel);
  const lane_int exits2 = (e_in != 0) & (db2 < parallel);
  const lane_float t0 = select(never, n0 / -db0, exits0);
  const lane_float t1 = select(never, n1 / -db1, exits1);
  const lane_float t2 = select(never, n2 / -db2, exits2);
  lane_int corner =
      select(select((lane_int)(2), (lane_int)(1), t1 <= t2), (lane_int)(0), (t0 <= t1) & (t0 <= t2));
  lane_float t_exit = fmin(t0, fmin(t1, t2));
  /* Only the entry edge lies ahead: rounding made a heading parallel to it look like it points
   * back. Crossing back is still a valid move (the step bound caps any ping-pong). */
  const lane_int back_corner = previous3(e_in);
  const lane_float back_rate = pick3(back_corner, db0, db1, db2);
  const lane_int back = !(exits0 | exits1 | exits2) & (e_in >= 0) & (back_rate < 0.0f);
  corner = select(corner, back_corner, back);
  t_exit = select(t_exit, pick3(back_corner, n0, n1, n2) / -back_rate, back);

  const lane_int crossing = w->walking & (exits0 | exits1 | exits2 | back) & (t_exit < w->remaining);
  const lane_int ending = w->walking & !crossing;

  piece->face = f;
  piece->start0 = piece->end0 = b0, piece->start1 = piece->end1 = b1, piece->start2 = piece->end2 = b2;
  piece->length = (lane_float)(0.0f);
  piece->walked = w->walking;

  /* Ending lanes walk what remains inside this face. (Each part is skipped when no lane needs it:
   * most steps of a walk cross, and only its last ends.) */
  if (LANE_ANY(ending)) {
    lane_float end0 = b0 + w->remaining * db0, end1 = b1 + w->remaining * db1, end2 = b2 + w->remaining * db2;
    clamp_barycentric_lanes(&end0, &end1, &end2);
    piece->end0 = w->b0 = select(b0, end0, ending);
    piece->end1 = w->b1 = select(b1, end1, ending);
    piece->end2 = w->b2 = select(b2, end2, ending);
    piece->length = select(piece->length, w->remaining, ending);
    w->remaining = select(w->remaining, (lane_float)(0.0f), ending);
    w->walking &= !ending;
  }
  if (!LANE_ANY(crossing)) return;

  /* Crossing lanes: the exit point on edge e, as a fraction s along it, from the two surviving
   * coordinates: exactly on the edge whatever rounding did to the point. */
  const lane_int e = next3(corner);
  const lane_int e_next = next3(e);
  const lane_float at0 = b0 + t_exit * db0, at1 = b1 + t_exit * db1, at2 = b2 + t_exit * db2;
  const lane_float weight_from = fmax(pick3(e, at0, at1, at2), 0.0f);
  const lane_float weight_to = fmax(pick3(e_next, at0, at1, at2), 0.0f);
  const lane_float total = weight_from + weight_to;
  const lane_float s = select((lane_float)(0.5f), clamp(weight_to / total, 0.0f, 1.0f), total > 0.0f);
  lane_float exit0, exit1, exit2;
  edge_point_lanes(e, s, &exit0, &exit1, &exit2);
  piece->end0 = w->b0 = select(w->b0, exit0, crossing);
  piece->end1 = w->b1 = select(w->b1, exit1, crossing);
  piece->end2 = w->b2 = select(w->b2, exit2, crossing);
  piece->length = select(piece->length, t_exit, crossing);
  w->remaining = select(w->remaining, w->remaining - t_exit, crossing);

  const lane_int g = GATHER_EDGE_FIELD(lane_int, faces, f, e, neighbour, lanes);
  const lane_int boundary = crossing & (g < 0);
  const lane_int through = crossing & (g >= 0);
  w->hit_boundary |= boundary;
#ifdef PHYSARUM_FAULT_NO_REFLECT
  /* planted fault: agents stop at the boundary instead of reflecting */
  w->walking &= !boundary;
#else
  if (!reflect) w->walking &= !boundary;
  else if (LANE_ANY(boundary)) {
    /* Mirror the heading about the edge line and walk on inside the same face. Edge e runs from
     * corner e to corner e+1: corner 0 = (0, 0), corner 1 = (x1, 0), corner 2 = (x2, y2). */
    const lane_float x1 = 1.0f / inv_x1, y2 = 1.0f / inv_y2, x2 = shear * x1 * y2;
    const lane_float edge_x = select(select(-x2, x2 - x1, e == 1), x1, e == 0);
    const lane_float edge_y = select(select(-y2, y2, e == 1), (lane_float)(0.0f), e == 0);
    const lane_float edge_length = sqrt(edge_x * edge_x + edge_y * edge_y);
    const lane_float ux = edge_x / edge_length, uy = edge_y / edge_length;
    const lane_float along = 2.0f * (dx * ux + dy * uy);
    const lane_float rx = along * ux - dx, ry = along * uy - dy;
    const lane_float r_length = sqrt(rx * rx + ry * ry);
    w->dx = select(w->dx, rx / r_length, boundary);
    w->dy = select(w->dy, ry / r_length, boundary);
    w->entry_edge = select(w->entry_edge, e, boundary);
  }
#endif
  if (!LANE_ANY(through)) return;

  /* Cross into g, where the shared edge runs from corner j+1 to corner j. */
  const lane_uint edges = GATHER_FIELD(lane_uint, faces, f, neighbour_edges, lanes);
  const lane_int j = CONVERT_LANE_INT(edges >> CONVERT_LANE_UINT(2 * e)) & 3;
  const lane_float c = GATHER_EDGE_FIELD(lane_float, faces, f, e, transition_cos, lanes);
  const lane_float sn = GATHER_EDGE_FIELD(lane_float, faces, f, e, transition_sin, lanes);
  lane_float next0, next1, next2;
  edge_point_lanes(j, 1.0f - s, &next0, &next1, &next2);
  w->dx = select(w->dx, c * dx - sn * dy, through);
  w->dy = select(w->dy, sn * dx + c * dy, through);
  w->b0 = select(w->b0, next0, through);
  w->b1 = select(w->b1, next1, through);
  w->b2 = select(w->b2, next2, through);
  w->face = select(w->face, g, through);
#if PHYSARUM_WALK_LANES > 1
  /* The faces entered, read at the top of this walker's next step: fetched now, they arrive while
   * the other walkers of the work-item take their steps (sensing_steering.cl, movement.cl). */
  PREFETCH_FACES(faces, w->face);
#endif
  w->entry_edge = select(w->entry_edge, j, through);
  w->face_crossings = select(w->face_crossings, w->face_crossings + 1, through);
}

typedef struct {
  int face;
  float2 position;
  float3 barycentric; /* of position */
  float2 heading;
  int hit_boundary;
  int face_crossings;
} TraceEnd;

/* Where the first `lanes` lanes of a walk ended, in ends[0 .. lanes) (a lane the step bound cut
 * short is clamped into its face). */
void walk_lane_ends(__global const PhysarumFaceRecord* faces, const WalkLanes* w, const int lanes, TraceEnd* ends) {
  lane_float b0 = w->b0, b1 = w->b1, b2 = w->b2;
  clamp_barycentric_lanes(&b0, &b1, &b2);
  for (int lane = 0; lane < lanes; ++lane) {
    TraceEnd r;
    r.face = int_in_lane(w->face, lane);
    r.barycentric = (float3)(float_in_lane(b0, lane), float_in_lane(b1, lane), float_in_lane(b2, lane));
    r.position = r.barycentric.y * face_corner1(faces, r.face) + r.barycentric.z * face_corner2(faces, r.face);
    r.heading = (float2)(float_in_lane(w->dx, lane), float_in_lane(w->dy, lane));
    r.hit_boundary = int_in_lane(w->hit_boundary, lane) != 0;
    r.face_crossings = int_in_lane(w->face_crossings, lane);
    ends[lane] = r;
  }
}

/* The three sensor walks of one agent (left, centre, right), which stop at boundaries, in lockstep:
 * lanes 0..2 of one walker with vector lanes, three walkers otherwise. Results in the order of the
 * directions. */
void trace_three_sensors(__global const PhysarumFaceRecord* faces, const int face, const float2 p, const float2 d0,
                         const float2 d1, const float2 d2, const float length, TraceEnd* end0, TraceEnd* end1,
                         TraceEnd* end2) {
  WalkPieces piece;
#if PHYSARUM_WALK_LANES > 1
  const lane_int first_three = LANE_INDICES < 3;
  const lane_float dx = with_lane(with_lane(with_lane((lane_float)(0.0f), 0, d0.x), 1, d1.x), 2, d2.x);
  const lane_float dy = with_lane(with_lane(with_lane((lane_float)(0.0f), 0, d0.y), 1, d1.y), 2, d2.y);
  WalkLanes w = walk_lanes_start(faces, 3, (lane_int)(face), (lane_float)(p.x), (lane_float)(p.y), dx, dy,
                                 (lane_float)(length), first_three);
  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS && LANE_ANY(w.walking); ++step)
    walk_lanes_step(faces, 3, &w, 0, &piece);
  TraceEnd ends[3];
  walk_lane_ends(faces, &w, 3, ends);
  *end0 = ends[0];
  *end1 = ends[1];
  *end2 = ends[2];
#else
  WalkLanes w0 = walk_lanes_start(faces, 1, face, p.x, p.y, d0.x, d0.y, length, 1);
  WalkLanes w1 = walk_lanes_start(faces, 1, face, p.x, p.y, d1.x, d1.y, length, 1);
  WalkLanes w2 = walk_lanes_start(faces, 1, face, p.x, p.y, d2.x, d2.y, length, 1);
  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS && (w0.walking | w1.walking | w2.walking); ++step) {
    if (w0.walking) walk_lanes_step(faces, 1, &w0, 0, &piece);
    if (w1.walking) walk_lanes_step(faces, 1, &w1, 0, &piece);
    if (w2.walking) walk_lanes_step(faces, 1, &w2, 0, &piece);
  }
  walk_lane_ends(faces, &w0, 1, end0);
  walk_lane_ends(faces, &w1, 1, end1);
  walk_lane_ends(faces, &w2, 1, end2);
#endif
}

#endif /* PHYSARUM_TRACE_CL */
