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
typedef int32_t dev_int;
typedef uint32_t dev_uint;
typedef float dev_float;
#endif

/* ---- field statistics (reduction.cl) ----
 * One partial per work-group, as four floats (a float4 on the device):
 *   [0] sum of m_i u_i,  [1..3] sum of m_i over the vertices with u_i > threshold[k]. */
#define PHYSARUM_FIELD_SUM_COMPONENTS 4
#define PHYSARUM_COVERAGE_THRESHOLDS 3

/* ---- conjugate gradients (pheromone.cl) ----
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

#endif /* PHYSARUM_DEVICE_TYPES_H */
