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

float3 face_direction_barycentric(const float x1, const float x2, const float y2, const float2 d) {
  const float db2 = d.y / y2;
  const float db1 = (d.x - db2 * x2) / x1;
  return (float3)(-db1 - db2, db1, db2);
}

float2 face_corner(const float x1, const float x2, const float y2, const int k) {
  return k == 0 ? (float2)(0.0f, 0.0f) : (k == 1 ? (float2)(x1, 0.0f) : (float2)(x2, y2));
}

float component3(const float3 v, const int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

/* A point that rounding left marginally outside its face, moved back onto it (barycentric
 * coordinates clamped at zero and renormalised): every walk ends inside its end face. */
float2 clamp_into_face(const float x1, const float x2, const float y2, const float2 p) {
  float3 b = face_point_barycentric(x1, x2, y2, p);
  if (b.x >= 0.0f && b.y >= 0.0f && b.z >= 0.0f && isfinite(b.x + b.y + b.z)) return p;
  b = (float3)(isfinite(b.x) ? fmax(b.x, 0.0f) : 0.0f, isfinite(b.y) ? fmax(b.y, 0.0f) : 0.0f,
               isfinite(b.z) ? fmax(b.z, 0.0f) : 0.0f);
  const float sum = b.x + b.y + b.z;
  if (!(sum > 0.0f)) return (float2)((x1 + x2) / 3.0f, y2 / 3.0f); /* the centroid */
  return (b.y * (float2)(x1, 0.0f) + b.z * (float2)(x2, y2)) / sum;
}

/* Directions within this relative tolerance of parallel to an edge do not cross it. The
 * reference uses 1e-12 in double; this is the same rule a few float ulps wide. */
#define PHYSARUM_PARALLEL_TOLERANCE 1e-6f

typedef struct {
  int face;
  float2 position;
  float2 heading;
  int hit_boundary;
  int face_crossings;
} TraceEnd;

/* Walks `length` from `p` in face `f` along unit `d`. reflect != 0: mirror at boundary edges and go
 * on (agents); reflect == 0: stop on the boundary (sensors). When deposit_amount != 0, each
 * per-face piece deposits deposit_amount * (piece length / length) at its midpoint. */
TraceEnd trace_walk(__global const PhysarumFaceRecord* faces, int f, float2 p, float2 d, const float length,
                    const int reflect, const float deposit_amount, __global PhysarumDepositCell* deposits,
                    const float deposit_scale) {
  TraceEnd result;
  result.hit_boundary = 0;
  result.face_crossings = 0;
  float remaining = length > 0.0f && isfinite(length) ? length : 0.0f;
  const float per_length = remaining > 0.0f ? deposit_amount / remaining : 0.0f;
  int entry_edge = -1;

  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS; ++step) {
    const float x1 = faces[f].x1, x2 = faces[f].x2, y2 = faces[f].y2;
    const float3 b = face_point_barycentric(x1, x2, y2, p);
    const float3 db = face_direction_barycentric(x1, x2, y2, d);
    const float parallel = -PHYSARUM_PARALLEL_TOLERANCE * (fabs(db.x) + fabs(db.y) + fabs(db.z));

    /* Leave where a decreasing barycentric coordinate reaches zero; coordinate k vanishes on edge
     * (k+1)%3. */
    float t_exit = INFINITY;
    int corner_exit = -1;
    for (int k = 0; k < 3; ++k) {
      const float dbk = component3(db, k);
      if ((k + 1) % 3 == entry_edge || !(dbk < parallel)) continue;
      const float t = fmax(component3(b, k), 0.0f) / -dbk;
      if (t < t_exit) {
        t_exit = t;
        corner_exit = k;
      }
    }
    if (corner_exit < 0 && entry_edge >= 0) {
      const int k = (entry_edge + 2) % 3;
      const float dbk = component3(db, k);
      if (dbk < 0.0f) {
        t_exit = fmax(component3(b, k), 0.0f) / -dbk;
        corner_exit = k;
      }
    }

    if (corner_exit < 0 || t_exit >= remaining) {
      const float2 end = clamp_into_face(x1, x2, y2, p + remaining * d);
      if (deposit_amount != 0.0f) {
        if (length > 0.0f) deposit_at_point(faces, f, 0.5f * (p + end), per_length * remaining, deposits, deposit_scale);
        else deposit_at_point(faces, f, end, deposit_amount, deposits, deposit_scale);
      }
      result.face = f;
      result.position = end;
      result.heading = d;
      return result;
    }

    const int e = (corner_exit + 1) % 3;
    const int e_next = (e + 1) % 3;
    const float weight_from = fmax(component3(b, e) + t_exit * component3(db, e), 0.0f);
    const float weight_to = fmax(component3(b, e_next) + t_exit * component3(db, e_next), 0.0f);
    const float total = weight_from + weight_to;
    const float s = total > 0.0f ? clamp(weight_to / total, 0.0f, 1.0f) : 0.5f;
    const float2 ce = face_corner(x1, x2, y2, e), ce_next = face_corner(x1, x2, y2, e_next);
    const float2 exit_point = (1.0f - s) * ce + s * ce_next;
    if (deposit_amount != 0.0f && t_exit > 0.0f)
      deposit_at_point(faces, f, 0.5f * (p + exit_point), per_length * t_exit, deposits, deposit_scale);
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
        result.position = exit_point;
        result.heading = d;
        return result;
      }
      const float2 u = normalize(ce_next - ce);
      d = normalize((2.0f * dot(d, u)) * u - d);
      p = exit_point;
      entry_edge = e;
      continue;
    }

    const int j = (int)((faces[f].neighbour_edges >> (2 * e)) & 3u);
    const float gx1 = faces[g].x1, gx2 = faces[g].x2, gy2 = faces[g].y2;
    p = (1.0f - s) * face_corner(gx1, gx2, gy2, (j + 1) % 3) + s * face_corner(gx1, gx2, gy2, j);
    const float c = faces[f].transition_cos[e], sn = faces[f].transition_sin[e];
    d = (float2)(c * d.x - sn * d.y, sn * d.x + c * d.y);
    f = g;
    entry_edge = j;
    ++result.face_crossings;
  }

  /* Step bound reached (pathological input only): end where the walk got to. */
  result.face = f;
  result.position = clamp_into_face(faces[f].x1, faces[f].x2, faces[f].y2, p);
  result.heading = d;
  return result;
}
