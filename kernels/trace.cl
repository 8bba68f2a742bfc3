/* Straight-line (geodesic) walking across intrinsic faces, in float32: the device twin of
 * common/trace.cpp, step for step (same exit rule, same exit-point construction, same reflection),
 * so a reader can compare them side by side. Differences are only those float32 forces: the
 * parallel tolerance is relative to float rounding, and positions are clamped into the end face.
 *
 * Deposition is folded into the walk (the reference collects segments and deposits afterwards): a
 * kernel cannot keep a variable-length segment list, and depositing each piece as it is walked is
 * the same sum. A walk with deposit_amount == 0 deposits nothing (sensors, inactive agents). */
#include "device_types.h"
#include "deposition.cl"

/* Barycentric coordinates of a point and their rates along a direction in a face frame (corner 0
 * at the origin, corner 1 on +x): a 2x2 triangular solve. */
float3 face_point_barycentric(const float x1, const float x2, const float y2, const float2 p) {
  const float b2 = p.y / y2;
  const float b1 = (p.x - b2 * x2) / x1;
  return (float3)(1.0f - b1 - b2, b1, b2);
}

float component3(const float3 v, const int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

float2 face_corner(const float x1, const float x2, const float y2, const int k) {
  return k == 0 ? (float2)(0.0f, 0.0f) : (k == 1 ? (float2)(x1, 0.0f) : (float2)(x2, y2));
}

float2 point_of_barycentric(const float x1, const float x2, const float y2, const float3 b) {
  return (float2)(b.y * x1 + b.z * x2, b.z * y2);
}

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

/* Directions within this relative tolerance of parallel to an edge do not cross it. The
 * reference uses 1e-12 in double; this is the same rule a few float ulps wide. */
#define PHYSARUM_PARALLEL_TOLERANCE 1e-6f

typedef struct {
  int face;
  float2 position;
  float3 barycentric; /* of position: sensors interpolate with it directly */
  float2 heading;
  int hit_boundary;
  int face_crossings;
} TraceEnd;

/* Walks `length` from `p` in face `f` along unit `d`. reflect != 0: mirror at boundary edges and go
 * on (agents); reflect == 0: stop on the boundary (sensors). When deposit_amount != 0, each
 * per-face piece deposits deposit_amount * (piece length / length) at its midpoint.
 *
 * Cost: the walk is a chain of dependent face reads, so each step does as little as it can. The
 * point's barycentric coordinates are carried along rather than solved for: after a crossing the
 * point lies on the shared edge, where they are (1 - s, s, 0) up to the corner order; only their
 * rate along the heading needs the new face's layout. The three exit times are computed without
 * branches and the nearest picked with selects (ties go to the lowest corner, as in the reference). */
TraceEnd trace_walk(__global const PhysarumFaceRecord* faces, int f, float2 p, float2 d, const float length,
                    const int reflect, const float deposit_amount, __global PhysarumDepositCell* deposits,
                    const float deposit_scale) {
  TraceEnd result;
  result.hit_boundary = 0;
  result.face_crossings = 0;
  float remaining = length > 0.0f && isfinite(length) ? length : 0.0f;
  const float per_length = remaining > 0.0f ? deposit_amount / remaining : 0.0f;
  int entry_edge = -1;
  float x1 = faces[f].x1, x2 = faces[f].x2, y2 = faces[f].y2;
  float3 b = face_point_barycentric(x1, x2, y2, p);

  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS; ++step) {
    const float inv_y2 = 1.0f / y2, inv_x1 = 1.0f / x1;
    const float db2 = d.y * inv_y2;
    const float db1 = (d.x - db2 * x2) * inv_x1;
    const float3 db = (float3)(-db1 - db2, db1, db2);
    const float parallel = -PHYSARUM_PARALLEL_TOLERANCE * (fabs(db.x) + fabs(db.y) + fabs(db.z));

    /* Leave where a decreasing coordinate reaches zero; coordinate k vanishes on edge (k+1)%3,
     * which must not be the edge just entered through. */
    const float t0 = (entry_edge != 1 && db.x < parallel) ? fmax(b.x, 0.0f) / -db.x : INFINITY;
    const float t1 = (entry_edge != 2 && db.y < parallel) ? fmax(b.y, 0.0f) / -db.y : INFINITY;
    const float t2 = (entry_edge != 0 && db.z < parallel) ? fmax(b.z, 0.0f) / -db.z : INFINITY;
    float t_exit = t0;
    int corner_exit = t0 < INFINITY ? 0 : -1;
    if (t1 < t_exit) {
      t_exit = t1;
      corner_exit = 1;
    }
    if (t2 < t_exit) {
      t_exit = t2;
      corner_exit = 2;
    }
    if (corner_exit < 0 && entry_edge >= 0) {
      /* Only the entry edge lies ahead: rounding made a heading parallel to it look like it
       * points back. Crossing back is still a valid move (the step bound caps any ping-pong). */
      const int k = (entry_edge + 2) % 3;
      const float dbk = component3(db, k);
      if (dbk < 0.0f) {
        t_exit = fmax(component3(b, k), 0.0f) / -dbk;
        corner_exit = k;
      }
    }

    if (corner_exit < 0 || t_exit >= remaining) {
      const float3 end = clamp_barycentric(b + remaining * db);
      if (deposit_amount != 0.0f)
        deposit_at_barycentric(faces, f, length > 0.0f ? 0.5f * (b + end) : end,
                               length > 0.0f ? per_length * remaining : deposit_amount, deposits, deposit_scale);
      result.face = f;
      result.barycentric = end;
      result.position = point_of_barycentric(x1, x2, y2, end);
      result.heading = d;
      return result;
    }

    /* Exit point on edge e, as a fraction s along it, from the two surviving coordinates: exactly
     * on the edge whatever rounding did to the point. */
    const int e = (corner_exit + 1) % 3;
    const int e_next = (e + 1) % 3;
    const float weight_from = fmax(component3(b, e) + t_exit * component3(db, e), 0.0f);
    const float weight_to = fmax(component3(b, e_next) + t_exit * component3(db, e_next), 0.0f);
    const float total = weight_from + weight_to;
    const float s = total > 0.0f ? clamp(weight_to / total, 0.0f, 1.0f) : 0.5f;
    const float3 exit_b = edge_point_barycentric(e, s);
    if (deposit_amount != 0.0f && t_exit > 0.0f)
      deposit_at_barycentric(faces, f, 0.5f * (b + exit_b), per_length * t_exit, deposits, deposit_scale);
    remaining -= t_exit;

    const int g = faces[f].neighbour[e];
    if (g < 0) {
      result.hit_boundary = 1;
#ifdef PHYSARUM_FAULT_NO_REFLECT
      /* planted fault: agents stop at the boundary instead of reflecting */
      if (1) {
#else
      if (!reflect) {
#endif
        result.face = f;
        result.barycentric = exit_b;
        result.position = point_of_barycentric(x1, x2, y2, exit_b);
        result.heading = d;
        return result;
      }
      /* Mirror the heading about the edge line and walk on inside the same face. */
      const float2 u = normalize(face_corner(x1, x2, y2, e_next) - face_corner(x1, x2, y2, e));
      d = normalize((2.0f * dot(d, u)) * u - d);
      b = exit_b;
      entry_edge = e;
      continue;
    }

    /* Cross into g, where the shared edge runs from corner j+1 to corner j. */
    const int j = (int)((faces[f].neighbour_edges >> (2 * e)) & 3u);
    const float c = faces[f].transition_cos[e], sn = faces[f].transition_sin[e];
    d = (float2)(c * d.x - sn * d.y, sn * d.x + c * d.y);
    b = edge_point_barycentric(j, 1.0f - s);
    f = g;
    x1 = faces[f].x1;
    x2 = faces[f].x2;
    y2 = faces[f].y2;
    entry_edge = j;
    ++result.face_crossings;
  }

  /* Step bound reached (pathological input only): end where the walk got to. */
  result.face = f;
  result.barycentric = clamp_barycentric(b);
  result.position = point_of_barycentric(x1, x2, y2, result.barycentric);
  result.heading = d;
  return result;
}
