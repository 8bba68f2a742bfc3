/* Straight-line (geodesic) walking across intrinsic faces, in float32: the device twin of
 * common/trace.cpp, step for step (same exit rule, same exit-point construction, same reflection),
 * so a reader can compare them side by side. Differences are only those float32 forces: the
 * parallel tolerance is relative to float rounding, and end points are clamped into the end face.
 *
 * Cost: a walk is a chain of dependent face reads, so each step does as little as it can.
 *   - The point's barycentric coordinates are carried along rather than solved for: after a
 *     crossing the point lies on the shared edge, where they are (1 - s, s, 0) up to the corner
 *     order; only their rate along the heading needs the new face's layout, and the face record
 *     stores that layout as reciprocals (device_types.h), so it costs multiplications only.
 *   - The nearest exit is chosen by cross-multiplied comparisons, with one division for its time.
 *   - The three sensors of an agent walk in lockstep (trace_three_sensors), so the processor
 *     overlaps three independent chains of face reads instead of waiting on one.
 * Deposition is folded into the movement walk (the reference collects segments and deposits
 * afterwards): a kernel cannot keep a variable-length segment list, and depositing each piece as it
 * is walked is the same sum. */
#ifndef PHYSARUM_TRACE_CL
#define PHYSARUM_TRACE_CL
#include "device_types.h"
#include "agents.cl"
#include "deposition.cl"

float component3(const float3 v, const int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

/* The barycentric coordinates of the point a fraction s along edge e (corner e to corner e+1). */
float3 edge_point_barycentric(const int e, const float s) {
  const int e_next = (e + 1) % 3;
  return (float3)(e == 0 ? 1.0f - s : (e_next == 0 ? s : 0.0f), e == 1 ? 1.0f - s : (e_next == 1 ? s : 0.0f),
                  e == 2 ? 1.0f - s : (e_next == 2 ? s : 0.0f));
}

/* Coordinates that rounding left marginally outside the face, clamped at zero and renormalised:
 * every walk ends inside its end face (the centroid when nothing usable is left). */
float3 clamp_barycentric(float3 b) {
  if (b.x >= 0.0f && b.y >= 0.0f && b.z >= 0.0f && isfinite(b.x + b.y + b.z)) return b;
  b = (float3)(isfinite(b.x) ? fmax(b.x, 0.0f) : 0.0f, isfinite(b.y) ? fmax(b.y, 0.0f) : 0.0f,
               isfinite(b.z) ? fmax(b.z, 0.0f) : 0.0f);
  const float sum = b.x + b.y + b.z;
  return sum > 0.0f ? b / sum : (float3)(1.0f / 3.0f);
}

float2 point_of_barycentric(__global const PhysarumFaceRecord* faces, const int face, const float3 b) {
  return b.y * face_corner1(faces, face) + b.z * face_corner2(faces, face);
}

/* Directions within this relative tolerance of parallel to an edge do not cross it. The
 * reference uses 1e-12 in double; this is the same rule a few float ulps wide. */
#define PHYSARUM_PARALLEL_TOLERANCE 1e-6f

#define WALKING 0
#define WALK_ENDED 1   /* the whole length was walked */
#define WALK_STOPPED 2 /* a sensor met the boundary */

/* One walk in progress. */
typedef struct {
  int face;
  float3 b;        /* barycentric coordinates of the current point in `face` */
  float2 d;        /* unit heading in `face`'s frame */
  float remaining; /* length still to walk */
  int entry_edge;  /* the edge just entered through (or reflected off): never an exit at t = 0 */
  int state;
  int hit_boundary;
  int face_crossings;
} Walker;

Walker walk_start(__global const PhysarumFaceRecord* faces, const int face, const float2 p, const float2 d,
                  const float length) {
  Walker w;
  w.face = face;
  w.b = barycentric_in_face(faces, face, p);
  w.d = d;
  w.remaining = length > 0.0f && isfinite(length) ? length : 0.0f;
  w.entry_edge = -1;
  w.state = WALKING;
  w.hit_boundary = 0;
  w.face_crossings = 0;
  return w;
}

/* One piece of a walk: from w->b to *piece_end (barycentric, in the face the walker was in,
 * *piece_face) of length *piece_length. Then the walker either ends, stops at a boundary (sensors:
 * reflect == 0), reflects (agents) or crosses into the neighbour. */
/* Inlined on purpose: the three sensor walkers must live in registers, not behind a pointer, for
 * their face reads to overlap (the attribute is a hint every clang-based OpenCL compiler honours). */
inline __attribute__((always_inline)) void walk_step(__global const PhysarumFaceRecord* faces, Walker* w,
                                                     const int reflect, int* piece_face, float3* piece_start,
                                                     float3* piece_end, float* piece_length) {
  const int f = w->face;
  const float3 b = w->b;
  const float2 d = w->d;
  *piece_face = f;
  *piece_start = b;
  const float db2 = d.y * faces[f].inv_y2;
  const float db1 = d.x * faces[f].inv_x1 - d.y * faces[f].shear;
  const float3 db = (float3)(-db1 - db2, db1, db2);
  const float parallel = -PHYSARUM_PARALLEL_TOLERANCE * (fabs(db.x) + fabs(db.y) + fabs(db.z));

  /* Leave where a decreasing coordinate reaches zero; coordinate k vanishes on edge (k+1)%3, which
   * must not be the edge just entered through. Exit time of k: n_k / q_k, compared without
   * dividing (q > 0): n_i / q_i < n_j / q_j  <=>  n_i q_j < n_j q_i. Ties keep the lower k. */
  const int e_in = w->entry_edge;
  const float n0 = fmax(b.x, 0.0f), n1 = fmax(b.y, 0.0f), n2 = fmax(b.z, 0.0f);
  const float q0 = -db.x, q1 = -db.y, q2 = -db.z;
  int corner_exit = (e_in != 1 && db.x < parallel) ? 0 : -1;
  float n = n0, q = q0;
  if (e_in != 2 && db.y < parallel && (corner_exit < 0 || n1 * q < n * q1)) corner_exit = 1, n = n1, q = q1;
  if (e_in != 0 && db.z < parallel && (corner_exit < 0 || n2 * q < n * q2)) corner_exit = 2, n = n2, q = q2;
  if (corner_exit < 0 && e_in >= 0) {
    /* Only the entry edge lies ahead: rounding made a heading parallel to it look like it points
     * back. Crossing back is still a valid move (the step bound caps any ping-pong). */
    const int k = (e_in + 2) % 3;
    if (component3(db, k) < 0.0f) corner_exit = k, n = fmax(component3(b, k), 0.0f), q = -component3(db, k);
  }

  if (corner_exit < 0 || n >= w->remaining * q) {
    *piece_end = clamp_barycentric(b + w->remaining * db);
    *piece_length = w->remaining;
    w->b = *piece_end;
    w->remaining = 0.0f;
    w->state = WALK_ENDED;
    return;
  }

  /* Exit point on edge e, as a fraction s along it, from the two surviving coordinates: exactly on
   * the edge whatever rounding did to the point. */
  const float t_exit = n / q;
  const int e = (corner_exit + 1) % 3;
  const int e_next = (e + 1) % 3;
  const float weight_from = fmax(component3(b, e) + t_exit * component3(db, e), 0.0f);
  const float weight_to = fmax(component3(b, e_next) + t_exit * component3(db, e_next), 0.0f);
  const float total = weight_from + weight_to;
  const float s = total > 0.0f ? clamp(weight_to / total, 0.0f, 1.0f) : 0.5f;
  const float3 exit_b = edge_point_barycentric(e, s);
  *piece_end = exit_b;
  *piece_length = t_exit;
  w->remaining -= t_exit;

  const int g = faces[f].neighbour[e];
  if (g < 0) {
    w->hit_boundary = 1;
#ifdef PHYSARUM_FAULT_NO_REFLECT
    /* planted fault: agents stop at the boundary instead of reflecting */
    if (1) {
#else
    if (!reflect) {
#endif
      w->b = exit_b;
      w->state = WALK_STOPPED;
      return;
    }
    /* Mirror the heading about the edge line and walk on inside the same face. */
    const float2 corner[3] = {(float2)(0.0f, 0.0f), face_corner1(faces, f), face_corner2(faces, f)};
    const float2 u = normalize(corner[e_next] - corner[e]);
    w->d = normalize((2.0f * dot(d, u)) * u - d);
    w->b = exit_b;
    w->entry_edge = e;
    return;
  }

  /* Cross into g, where the shared edge runs from corner j+1 to corner j. */
  const int j = (int)((faces[f].neighbour_edges >> (2 * e)) & 3u);
  const float c = faces[f].transition_cos[e], sn = faces[f].transition_sin[e];
  w->d = (float2)(c * d.x - sn * d.y, sn * d.x + c * d.y);
  w->b = edge_point_barycentric(j, 1.0f - s);
  w->face = g;
  w->entry_edge = j;
  w->face_crossings += 1;
}

typedef struct {
  int face;
  float2 position;
  float3 barycentric; /* of position */
  float2 heading;
  int hit_boundary;
  int face_crossings;
} TraceEnd;

TraceEnd walk_end(__global const PhysarumFaceRecord* faces, const Walker* w) {
  TraceEnd r;
  r.face = w->face;
  r.barycentric = w->state == WALKING ? clamp_barycentric(w->b) : w->b;
  r.position = point_of_barycentric(faces, w->face, r.barycentric);
  r.heading = w->d;
  r.hit_boundary = w->hit_boundary;
  r.face_crossings = w->face_crossings;
  return r;
}

/* The movement walk: `length` from p along unit d, reflecting at boundaries; when deposit_amount
 * != 0 each piece deposits deposit_amount * (piece length / length) at its midpoint (the whole
 * amount at the end point when length is 0). */
TraceEnd trace_walk(__global const PhysarumFaceRecord* faces, const int face, const float2 p, const float2 d,
                    const float length, const float deposit_amount, __global PhysarumDepositCell* deposits,
                    const float deposit_scale) {
  Walker w = walk_start(faces, face, p, d, length);
  const float per_length = w.remaining > 0.0f ? deposit_amount / w.remaining : 0.0f;
  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS && w.state == WALKING; ++step) {
    int piece_face;
    float3 from, to;
    float piece_length;
    walk_step(faces, &w, 1, &piece_face, &from, &to, &piece_length);
    if (deposit_amount == 0.0f) continue;
    if (!(length > 0.0f)) deposit_at_barycentric(faces, piece_face, to, deposit_amount, deposits, deposit_scale);
    else if (piece_length > 0.0f)
      deposit_at_barycentric(faces, piece_face, 0.5f * (from + to), per_length * piece_length, deposits, deposit_scale);
  }
  return walk_end(faces, &w);
}

/* The three sensor walks of one agent (left, centre, right), which stop at boundaries, advanced in
 * lockstep. Results in the order of the directions. */
void trace_three_sensors(__global const PhysarumFaceRecord* faces, const int face, const float2 p, const float2 d0,
                         const float2 d1, const float2 d2, const float length, TraceEnd* end0, TraceEnd* end1,
                         TraceEnd* end2) {
  Walker w0 = walk_start(faces, face, p, d0, length);
  Walker w1 = walk_start(faces, face, p, d1, length);
  Walker w2 = walk_start(faces, face, p, d2, length);
  int piece_face;
  float3 from, to;
  float piece_length;
  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS; ++step) {
    if (w0.state == WALKING) walk_step(faces, &w0, 0, &piece_face, &from, &to, &piece_length);
    if (w1.state == WALKING) walk_step(faces, &w1, 0, &piece_face, &from, &to, &piece_length);
    if (w2.state == WALKING) walk_step(faces, &w2, 0, &piece_face, &from, &to, &piece_length);
    if (w0.state != WALKING && w1.state != WALKING && w2.state != WALKING) break;
  }
  *end0 = walk_end(faces, &w0);
  *end1 = walk_end(faces, &w1);
  *end2 = walk_end(faces, &w2);
}

#endif /* PHYSARUM_TRACE_CL */
