/* The SIMD-lane layer of the walks (trace.cl, movement.cl, sensing_steering.cl): lane_float,
 * lane_int and lane_uint are float4/int4/uint4, float16/int16/uint16 or scalars by
 * PHYSARUM_WALK_LANES, with the per-lane reads, prefetches and lane accessors written once for all. */
#ifndef PHYSARUM_LANES_H
#define PHYSARUM_LANES_H

/* Walk lanes. A walker advances PHYSARUM_WALK_LANES walks at once (a build option the host sets):
 * on CPUs 4 (float4) for the moves of the agents of one work-item and 16 (float16) for the sensor
 * rays of five agents (sensing_steering.cl), so one instruction does the arithmetic of several walks
 * and their face reads are in flight together; 1 on GPUs, as scalars, since a GPU's threads are its
 * lanes already and idle vector lanes would only cost instructions. The code below is written once
 * for all: masks are comparison results combined with & | ! (true is -1 in a vector, 1 in a scalar;
 * both work with select), and the helpers here hide the rest. Results are the same bits either way. */
#ifndef PHYSARUM_WALK_LANES
#define PHYSARUM_WALK_LANES 1
#endif
/* A hint to fetch the cache line at p. On PoCL's CPU devices the host asks for clang's prefetch
 * (PHYSARUM_CLANG_PREFETCH): PoCL's OpenCL prefetch() does nothing. Elsewhere OpenCL's (a driver
 * that compiles through SPIR-V, as Mesa's rusticl, cannot take clang's). */
#ifdef PHYSARUM_CLANG_PREFETCH
#define PHYSARUM_PREFETCH(p) __builtin_prefetch(p)
#else
#define PHYSARUM_PREFETCH(p) prefetch((__global const float16*)(p), 1)
#endif
#if PHYSARUM_WALK_LANES == 4 || PHYSARUM_WALK_LANES == 16
#if PHYSARUM_WALK_LANES == 4
typedef float4 lane_float;
typedef int4 lane_int;
typedef uint4 lane_uint;
#define CONVERT_LANE_INT convert_int4
#define CONVERT_LANE_UINT convert_uint4
#define LANE_INDICES ((int4)(0, 1, 2, 3))
/* Per-lane reads of one face-record field (each lane its own face f, and its own edge e). With
 * lanes == 1 (a compile-time constant where the walk is inlined) only lane 0's face is read, so a
 * lone walk pays for one read, not four. */
#define GATHER_FIELD(type, faces, f, field, lanes)                                                     \
  ((lanes) == 1 ? (type)((faces)[(f).x].field)                                                         \
                : (type)((faces)[(f).x].field, (faces)[(f).y].field, (faces)[(f).z].field, (faces)[(f).w].field))
#define GATHER_EDGE_FIELD(type, faces, f, e, field, lanes)                                           \
  ((lanes) == 1 ? (type)((faces)[(f).x].field[(e).x])                                                \
                : (type)((faces)[(f).x].field[(e).x], (faces)[(f).y].field[(e).y],                   \
                         (faces)[(f).z].field[(e).z], (faces)[(f).w].field[(e).w]))
#define PREFETCH_FACES(faces, f)                                                                   \
  PHYSARUM_PREFETCH(&(faces)[(f).x]); PHYSARUM_PREFETCH(&(faces)[(f).y]);                           \
  PHYSARUM_PREFETCH(&(faces)[(f).z]); PHYSARUM_PREFETCH(&(faces)[(f).w]);
#else
typedef float16 lane_float;
typedef int16 lane_int;
typedef uint16 lane_uint;
#define CONVERT_LANE_INT convert_int16
#define CONVERT_LANE_UINT convert_uint16
#define LANE_INDICES ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
/* Lane i's face record (i a hexadecimal digit: .s0 .. .sf). */
#define FACE_OF_LANE(faces, f_, i) (faces)[(f_).s##i]
#define GATHER_FIELD(type, faces, f_, field, lanes)                             \
  ((type)(FACE_OF_LANE(faces, f_, 0).field, FACE_OF_LANE(faces, f_, 1).field,   \
          FACE_OF_LANE(faces, f_, 2).field, FACE_OF_LANE(faces, f_, 3).field,   \
          FACE_OF_LANE(faces, f_, 4).field, FACE_OF_LANE(faces, f_, 5).field,   \
          FACE_OF_LANE(faces, f_, 6).field, FACE_OF_LANE(faces, f_, 7).field,   \
          FACE_OF_LANE(faces, f_, 8).field, FACE_OF_LANE(faces, f_, 9).field,   \
          FACE_OF_LANE(faces, f_, a).field, FACE_OF_LANE(faces, f_, b).field,   \
          FACE_OF_LANE(faces, f_, c).field, FACE_OF_LANE(faces, f_, d).field,   \
          FACE_OF_LANE(faces, f_, e).field, FACE_OF_LANE(faces, f_, f).field))
#define PREFETCH_FACES(faces, f_)                                                                  \
  PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 0)); PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 1));  \
  PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 2)); PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 3));  \
  PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 4)); PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 5));  \
  PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 6)); PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 7));  \
  PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 8)); PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, 9));  \
  PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, a)); PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, b));  \
  PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, c)); PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, d));  \
  PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, e)); PHYSARUM_PREFETCH(&FACE_OF_LANE(faces, f_, f));
#define GATHER_EDGE_FIELD(type, faces, f_, e_, field, lanes)                                      \
  ((type)(FACE_OF_LANE(faces, f_, 0).field[(e_).s0], FACE_OF_LANE(faces, f_, 1).field[(e_).s1],   \
          FACE_OF_LANE(faces, f_, 2).field[(e_).s2], FACE_OF_LANE(faces, f_, 3).field[(e_).s3],   \
          FACE_OF_LANE(faces, f_, 4).field[(e_).s4], FACE_OF_LANE(faces, f_, 5).field[(e_).s5],   \
          FACE_OF_LANE(faces, f_, 6).field[(e_).s6], FACE_OF_LANE(faces, f_, 7).field[(e_).s7],   \
          FACE_OF_LANE(faces, f_, 8).field[(e_).s8], FACE_OF_LANE(faces, f_, 9).field[(e_).s9],   \
          FACE_OF_LANE(faces, f_, a).field[(e_).sa], FACE_OF_LANE(faces, f_, b).field[(e_).sb],   \
          FACE_OF_LANE(faces, f_, c).field[(e_).sc], FACE_OF_LANE(faces, f_, d).field[(e_).sd],   \
          FACE_OF_LANE(faces, f_, e).field[(e_).se], FACE_OF_LANE(faces, f_, f).field[(e_).sf]))
#endif
#define LANE_ANY(mask) any(mask)
/* Lane `lane` of a private vector, read through its elements in memory (the lane need not be a
 * compile-time constant). */
float float_in_lane(const lane_float v, const int lane) { return ((const float*)&v)[lane]; }
int int_in_lane(const lane_int v, const int lane) { return ((const int*)&v)[lane]; }
/* v with lane `lane` set to x (lane a compile-time constant where this is inlined). */
lane_float with_lane(const lane_float v, const int lane, const float x) {
  return select(v, (lane_float)(x), LANE_INDICES == lane);
}
lane_int with_lane_int(const lane_int v, const int lane, const int x) {
  return select(v, (lane_int)(x), LANE_INDICES == lane);
}
#elif PHYSARUM_WALK_LANES == 1
typedef float lane_float;
typedef int lane_int;
typedef uint lane_uint;
#define LANE_ANY(mask) ((mask) != 0)
#define CONVERT_LANE_INT convert_int
#define CONVERT_LANE_UINT convert_uint
#define GATHER_FIELD(type, faces, f, field, lanes) ((faces)[(f)].field)
#define GATHER_EDGE_FIELD(type, faces, f, e, field, lanes) ((faces)[(f)].field[(e)])
float float_in_lane(const float v, const int lane) { return v; }
int int_in_lane(const int v, const int lane) { return v; }
float with_lane(const float v, const int lane, const float x) { return lane == 0 ? x : v; }
int with_lane_int(const int v, const int lane, const int x) { return lane == 0 ? x : v; }
#else
#error "PHYSARUM_WALK_LANES must be 1, 4 or 16"
#endif

/* Per lane, component k (0, 1 or 2) of a three-component quantity held as three vectors. */
lane_float pick3(const lane_int k, const lane_float v0, const lane_float v1, const lane_float v2) {
  return select(select(v2, v1, k == 1), v0, k == 0);
}

/* (k + 1) % 3 and (k + 2) % 3 per lane, for k in 0..2. */
lane_int next3(const lane_int k) { return select(k + 1, (lane_int)(0), k == 2); }
lane_int previous3(const lane_int k) { return select(k - 1, (lane_int)(2), k == 0); }

#endif /* PHYSARUM_LANES_H */
