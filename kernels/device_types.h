/* Structs and constants shared by the host (C++, included from the opencl/ sources) and the kernels
 * (OpenCL C 1.2). Plain C only: every field is 4 bytes wide so both compilers lay the structs out
 * identically without packing pragmas. Types come from dev_* typedefs rather than cl_* ones so the
 * same text means the same thing on both sides. */
#ifndef PHYSARUM_DEVICE_TYPES_H
#define PHYSARUM_DEVICE_TYPES_H

#ifdef __OPENCL_VERSION__
typedef int dev_int;
typedef uint dev_uint;
typedef float dev_float;
#else
#include <stdint.h>
/* The host takes the number of agent parameters from its table. */
#include <common/model/model_parameters.hpp>
#define PHYSARUM_AGENT_PARAMETER_COUNT (physarum::kAgentParamCount)
typedef int32_t dev_int;
typedef uint32_t dev_uint;
typedef float dev_float;
#endif

/* ---- field statistics (reduction.cl) ----
 * One partial per work-group, as four floats (a float4 on the device):
 *   [0] sum of m_i u_i,  [1..3] sum of m_i over the vertices with u_i > threshold[k]. */
#define PHYSARUM_FIELD_SUM_COMPONENTS 4
#define PHYSARUM_COVERAGE_THRESHOLDS 3

/* ---- hybrid ELL + CSR matrices (diffusion_decay.cl, opencl/hybrid_matrix.hpp) ----
 * Entries per row in the fixed-width ELL block. A row of the sub-step matrix has its vertex's degree
 * plus one entries, 7 on average on a triangle mesh; 8 slots hold nearly every row of the intrinsic
 * Delaunay meshes whole, and the few longer rows spill into the overflow part (bench/README.md,
 * "Tuning measurements"). */
#define PHYSARUM_ELL_WIDTH 8

/* ---- conjugate gradients (conjugate_gradients.cl) ----
 * The scalars of one solve live on the device so iterations run without a host round trip; the
 * host reads this struct only every few iterations to see whether the solve has stopped. */
#define PHYSARUM_CG_RUNNING 0
#define PHYSARUM_CG_CONVERGED 1
#define PHYSARUM_CG_BREAKDOWN 2 /* p.Sp <= 0: the system is not positive definite in float */

typedef struct {
  dev_float rz;          /* r . z (z = Jacobi-preconditioned residual) */
  dev_float pq;          /* p . S p */
  dev_float rr;          /* r . r, the squared residual norm */
  dev_float stop_rr;     /* tolerance^2 * b . b: stop when rr <= stop_rr */
  dev_float bb;          /* b . b */
  dev_float beta;        /* rz_new / rz for the next search direction */
  dev_int status;        /* PHYSARUM_CG_RUNNING, _CONVERGED or _BREAKDOWN */
  dev_int iterations;    /* completed iterations */
} PhysarumCgState;


/* ---- the surface, as the agent kernels read it (opencl/face_records.cpp builds it) ----
 * One 64-byte record per intrinsic face, so a trace step touches one cache line. The face frame is
 * the SurfaceDomain's: corner 0 at the origin, corner 1 at (x1, 0), corner 2 at (x2, y2). The
 * record holds the layout in the form a trace step needs, free of divisions: barycentric
 * coordinates of a point p are b2 = p.y inv_y2, b1 = p.x inv_x1 - p.y shear, b0 = 1 - b1 - b2,
 * with inv_x1 = 1/x1, inv_y2 = 1/y2, shear = x2 / (x1 y2); the corners themselves (needed only
 * at a walk's end and at reflections) follow as x1 = 1/inv_x1, y2 = 1/inv_y2, x2 = shear x1 y2.
 * Edge i runs from corner i to corner (i+1)%3; across it lies face neighbour[i] (-1 on a boundary),
 * where the same edge has index (neighbour_edges >> 2i) & 3. Crossing edge i rotates a direction by
 * (transition_cos[i], transition_sin[i]); points are rebuilt from the neighbour's own corners, so no
 * translation is needed. */
typedef struct {
  dev_float inv_x1, shear, inv_y2; /* the layout, see above */
  dev_uint neighbour_edges;    /* 2 bits per edge */
  dev_int neighbour[3];
  dev_int vertex[3];
  dev_float transition_cos[3];
  dev_float transition_sin[3];
} PhysarumFaceRecord;

/* ---- agent parameters, per vertex or uniform (common/model/model_parameters.hpp) ----
 * One float per agent parameter of the host's parameter table, in table order. The kernels see it
 * as a struct of named floats that the host generates from the table (opencl/agent_parameters.cpp
 * provides "agent_parameters.h"); the host sees the same floats as an array. */
#ifdef __OPENCL_VERSION__
#include "agent_parameters.h"
#else
typedef struct {
  dev_float value[PHYSARUM_AGENT_PARAMETER_COUNT];
} PhysarumAgentParameters;
#endif

/* ---- one agent step: everything that is the same for every agent ---- */
typedef struct {
  dev_float dt;               /* s */
  dev_float deposit_scale;    /* fixed-point units per amount (a power of two) */
  dev_uint seed;
  dev_uint step;              /* index n of the step being taken */
  dev_int agent_count;
  dev_int face_count;
  dev_int uniform_parameters; /* 1: every vertex has `uniform`, the per-vertex array is not read */
  dev_int pad;
  PhysarumAgentParameters uniform;
} PhysarumStepConstants;

/* Per-agent counters the host sums on demand (run.json): crossings by movement and by sensors,
 * boundary reflections, respawns. */
#define PHYSARUM_COUNTER_MOVE_CROSSINGS 0
#define PHYSARUM_COUNTER_SENSOR_CROSSINGS 1
#define PHYSARUM_COUNTER_BOUNDARY_HITS 2
#define PHYSARUM_COUNTER_RESPAWNS 3
#define PHYSARUM_COUNTERS 4

/* Purposes of the Philox counter: the values of common/base/random_streams.hpp (never renumber). */
#define PHYSARUM_PURPOSE_INITIAL_PLACEMENT 1u
#define PHYSARUM_PURPOSE_INITIAL_STATE 2u
#define PHYSARUM_PURPOSE_TURN_DIRECTION 3u
#define PHYSARUM_PURPOSE_RESPAWN_PLACEMENT 4u
#define PHYSARUM_PURPOSE_RESPAWN_STATE 5u
#define PHYSARUM_PURPOSE_INITIAL_SPAWN_CORNER 6u
#define PHYSARUM_PURPOSE_RESPAWN_CORNER 7u

/* Bounds shared with the reference (common/surface/trace.hpp, reference/sensing_steering.hpp). */
#define PHYSARUM_MAX_TRACE_STEPS 65536
#define PHYSARUM_MAX_TURN_DECISIONS_PER_STEP 4
#define PHYSARUM_TURN_DECISION_TOLERANCE 1e-4f

/* Sensing with vector lanes (sensing_steering.cl): walkers of 16 lanes (five agents' three sensor
 * traces each) that take turns step by step in one work-item, so the face reads of some are in
 * flight while the others compute. Three: fewer leave face-read latency exposed, more spill
 * registers (bench/README.md, "Tuning measurements"). */
#define PHYSARUM_SENSING_WALKERS 3
#define PHYSARUM_SENSING_AGENTS_PER_WALKER 5 /* 15 of 16 lanes */

/* Movement with vector lanes (movement.cl): walkers of 4 lanes (four agents' moves) that take turns
 * step by step in one work-item, for the same reason. */
#define PHYSARUM_VECTOR_MOVE_WALKERS 3

#endif /* PHYSARUM_DEVICE_TYPES_H */
