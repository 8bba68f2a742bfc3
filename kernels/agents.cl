/* The agent population on the device (mirrors reference/agents.cpp): random streams, parameter
 * interpolation, uniform points on the surface, and the initial state. Agent state lives in
 * structure-of-arrays buffers, one array per attribute, in the order of reference/agents.hpp. Each
 * agent also carries its id: the key of its random streams, so the numbers it draws do not depend
 * on where it sits in the arrays (agents are reordered by face for memory locality). */
#ifndef PHYSARUM_AGENTS_CL
#define PHYSARUM_AGENTS_CL
#include "device_types.h"
#include <Random123/philox.h>
#include "species.cl"

/* ---- random numbers: the packing of common/base/philox.hpp and common/base/random_streams.hpp ---- */

uint4 agent_random_words(const uint seed, const uint agent, const uint step, const uint purpose, const uint index) {
  philox4x32_ctr_t c = {{step, purpose, index, 0u}};
  philox4x32_key_t k = {{seed, agent}};
  const philox4x32_ctr_t r = philox4x32_R(10, c, k);
  return (uint4)(r.v[0], r.v[1], r.v[2], r.v[3]);
}

/* Uniform in (0, 1) from one word, exactly as uniform01_float on the host. The reference's
 * first_uniform / second_uniform use two words in double; this is the same number to 2^-23. */
float uniform01(const uint word) { return (float)(word >> 9) * 0x1p-23f + 0x1p-24f; }
float first_uniform(const uint4 w) { return uniform01(w.x); }
float second_uniform(const uint4 w) { return uniform01(w.z); }

/* ---- fields at a point ---- */

float3 barycentric_in_face(__global const PhysarumFaceRecord* faces, const int face, const float2 p) {
  const float b2 = p.y * faces[face].inv_y2;
  const float b1 = p.x * faces[face].inv_x1 - p.y * faces[face].shear;
  return (float3)(1.0f - b1 - b2, b1, b2);
}

/* The corners of a face's layout: corner 1 at (x1, 0), corner 2 at (x2, y2). */
float2 face_corner1(__global const PhysarumFaceRecord* faces, const int face) {
  return (float2)(1.0f / faces[face].inv_x1, 0.0f);
}
float2 face_corner2(__global const PhysarumFaceRecord* faces, const int face) {
  const float x1 = 1.0f / faces[face].inv_x1, y2 = 1.0f / faces[face].inv_y2;
  return (float2)(faces[face].shear * x1 * y2, y2);
}

/* Every agent parameter at a point (paper Sec. 3.3: maps live at vertices and are interpolated).
 * A uniform scene reads no per-vertex memory at all. */
void parameters_at(const PhysarumStepConstants* k, __global const PhysarumFaceRecord* faces,
                   __global const PhysarumAgentParameters* vertex_parameters, const int face, const float2 p,
                   PhysarumAgentParameters* r) {
  *r = k->uniform;
  if (k->uniform_parameters) return;
#ifdef PHYSARUM_FAULT_MAP_AT_CENTROID
  /* planted fault: parameter maps read at the face centroid instead of interpolated at the point */
  (void)p;
  const float3 b = (float3)(1.0f / 3.0f);
#else
  const float3 b = barycentric_in_face(faces, face, p);
#endif
  /* Only the mapped parameters (PHYSARUM_MAPPED_*) vary and are interpolated; the others keep their
   * uniform values and read no vertex memory. */
  const int v0 = faces[face].vertex[0], v1 = faces[face].vertex[1], v2 = faces[face].vertex[2];
  PHYSARUM_BLEND_MAPPED_AGENT_PARAMETERS((*r), vertex_parameters[v0], vertex_parameters[v1], vertex_parameters[v2], b)
}

/* ---- uniform points and headings ---- */

/* Vose alias sampling. The bucket is floor(w * n / 2^32), exact in integers for any n; the
 * reference's floor(u * n) with a 52-bit u is the same bucket except within 2^-20 of a bucket edge. */
int sample_face(__global const float* alias_probability, __global const int* alias_index, const int face_count,
                const uint4 w) {
  const int bucket = (int)mul_hi(w.x, (uint)face_count);
#ifdef PHYSARUM_FAULT_UNIFORM_FACE
  return bucket; /* planted fault: every face equally likely, whatever its area */
#endif
  return second_uniform(w) < alias_probability[bucket] ? bucket : alias_index[bucket];
}

typedef struct {
  int face;
  float2 position;
} FacePoint;

/* A uniform point of the surface: face by the alias table, point by the square-root trick. */
/* The alias table is the domain's (indices in domain order, so draws match the reference's);
 * device_face maps its answer to the face's place in the device's locality order. */
FacePoint sample_surface_point(__global const PhysarumFaceRecord* faces, __global const float* alias_probability,
                               __global const int* alias_index, __global const int* device_face, const int face_count,
                               const uint4 face_choice, const uint4 in_face) {
  FacePoint p;
  p.face = device_face[sample_face(alias_probability, alias_index, face_count, face_choice)];
  const float s = sqrt(first_uniform(in_face));
  const float r2 = second_uniform(in_face);
  p.position = s * (1.0f - r2) * face_corner1(faces, p.face) + s * r2 * face_corner2(faces, p.face);
  return p;
}

/* ---- spawn weights (common/model/spawn_distribution.hpp; compiled in with PHYSARUM_SPAWN_WEIGHTS) ----
 * The face from the spawn distribution's own alias table (area x mean corner weight, zero where a
 * face touches a sink), the point from the linear density: a corner with probability w_i / sum w,
 * its coordinate Beta(2, 2) by the closed-form inverse CDF, the rest split uniformly. Bounded work:
 * no rejection loop. */
float beta22_from_uniform(const float u) { return 0.5f + sin(asin(2.0f * u - 1.0f) / 3.0f); }

/* A (re)spawn point: the base model's uniform point, or (PHYSARUM_SPAWN_WEIGHTS) the weighted one.
 * The draws are the reference's: `placement` blocks 0 and 1, and block 0 of `corner_purpose` for
 * the corner. */
FacePoint spawn_point(__global const PhysarumFaceRecord* faces, __global const float* alias_probability,
                      __global const int* alias_index, __global const float* spawn_alias_probability,
                      __global const int* spawn_alias_index, __global const float* spawn_weight,
                      __global const int* device_face, const int face_count, const uint seed, const uint agent,
                      const uint step, const uint placement, const uint corner_purpose) {
  const uint4 face_choice = agent_random_words(seed, agent, step, placement, 0u);
  const uint4 in_face = agent_random_words(seed, agent, step, placement, 1u);
#if defined(PHYSARUM_SPAWN_WEIGHTS) && !defined(PHYSARUM_FAULT_SPAWN_WEIGHTS_IGNORED)
  (void)alias_probability, (void)alias_index;
  FacePoint p;
  p.face = device_face[sample_face(spawn_alias_probability, spawn_alias_index, face_count, face_choice)];
  const float w0 = spawn_weight[faces[p.face].vertex[0]];
  const float w1 = spawn_weight[faces[p.face].vertex[1]];
  const float w2 = spawn_weight[faces[p.face].vertex[2]];
  const float target = first_uniform(agent_random_words(seed, agent, step, corner_purpose, 0u)) * (w0 + w1 + w2);
  const int corner = target < w0 ? 0 : (target < w0 + w1 ? 1 : 2);
  const float toward = beta22_from_uniform(first_uniform(in_face));
  const float split = second_uniform(in_face);
  const float rest_a = (1.0f - toward) * (1.0f - split), rest_b = (1.0f - toward) * split;
  /* b1, b2 (corner 0 sits at the origin of the face frame, so b0 needs no term) */
  const float b1 = corner == 1 ? toward : (corner == 0 ? rest_a : rest_b);
  const float b2 = corner == 2 ? toward : (corner == 1 ? rest_a : rest_b);
  p.position = b1 * face_corner1(faces, p.face) + b2 * face_corner2(faces, p.face);
  return p;
#else
  /* Without spawn weights (or with the planted fault spawn-weights-ignored): uniform by area. */
  (void)spawn_alias_probability, (void)spawn_alias_index, (void)spawn_weight, (void)corner_purpose;
  return sample_surface_point(faces, alias_probability, alias_index, device_face, face_count, face_choice, in_face);
#endif
}

float2 heading_from_uniform(const float u) {
  float c;
  const float s = sincos(2.0f * M_PI_F * u, &c);
  return (float2)(c, s);
}

float exponential_exposure(const float u) { return -log(u); }

/* The symmetry n of the directional bias (bias.cl), a build option when the controls have one. */
#ifndef PHYSARUM_BIAS_SYMMETRY
#define PHYSARUM_BIAS_SYMMETRY 1
#endif

/* A newborn's heading from the uniform u of its heading draw: random, or (PHYSARUM_SPAWN_HEADING_BIAS,
 * Fig. 8) along copy floor(u n) of its face's bias direction, random where that is zero (mirrors
 * heading_along_bias in common/model/directional_bias.cpp). */
float2 spawn_heading(__global const float2* bias_direction, const int face, const float u) {
#ifdef PHYSARUM_SPAWN_HEADING_BIAS
  const float2 d = bias_direction[face];
  if (d.x == 0.0f && d.y == 0.0f) return heading_from_uniform(u);
  const int copy = min((int)(u * (float)PHYSARUM_BIAS_SYMMETRY), PHYSARUM_BIAS_SYMMETRY - 1);
  const float angle = atan2(d.y, d.x) + 2.0f * M_PI_F * (float)copy / (float)PHYSARUM_BIAS_SYMMETRY;
  float c;
  const float s = sincos(angle, &c);
  return (float2)(c, s);
#else
  (void)bias_direction, (void)face;
  return heading_from_uniform(u);
#endif
}

/* ---- the initial state: reference/agents.hpp explains the steady-state draw ---- */
__kernel void initialise_agents(const PhysarumStepConstants k, __global const PhysarumFaceRecord* faces,
                                __global const PhysarumAgentParameters* vertex_parameters,
                                __global const float* alias_probability, __global const int* alias_index,
                                __global const float* spawn_alias_probability, __global const int* spawn_alias_index,
                                __global const float* spawn_weight, __global const float2* bias_direction,
                                __global const int* device_face, __global int* face, __global float2* position, __global float2* heading,
                                __global float* age, __global float* exposure, __global float* exposure_threshold,
                                __global float* time_since_decision, __global float* accumulated_turn,
                                __global uint* id) {
  const int a = get_global_id(0);
  if (a >= k.agent_count) return;
  const uint agent = (uint)a;
  const FacePoint p = spawn_point(faces, alias_probability, alias_index, spawn_alias_probability, spawn_alias_index,
                                  spawn_weight, device_face, k.face_count, k.seed, agent, 0u,
                                  PHYSARUM_PURPOSE_INITIAL_PLACEMENT, PHYSARUM_PURPOSE_INITIAL_SPAWN_CORNER);
  const uint4 state = agent_random_words(k.seed, agent, 0u, PHYSARUM_PURPOSE_INITIAL_STATE, 0u);
  face[a] = p.face;
  position[a] = p.position;
  heading[a] = spawn_heading(bias_direction, p.face, first_uniform(state));
  id[a] = agent;
  PhysarumAgentParameters here;
#ifdef PHYSARUM_SPECIES
  parameters_at(&k, faces, vertex_parameters + species_of(agent) * PHYSARUM_SPECIES_VERTICES, p.face, p.position, &here);
#else
  parameters_at(&k, faces, vertex_parameters, p.face, p.position, &here);
#endif
  const uint4 remaining = agent_random_words(k.seed, agent, 0u, PHYSARUM_PURPOSE_INITIAL_STATE, 1u);
  time_since_decision[a] = second_uniform(remaining) / here.turn_frequency;
  accumulated_turn[a] = here.turn_rate * time_since_decision[a];
  const float hazard = here.hazard_rate;
  if (hazard > 0.0f) {
    const float elapsed = exponential_exposure(second_uniform(state));
    exposure[a] = elapsed;
    exposure_threshold[a] = elapsed + exponential_exposure(first_uniform(remaining));
    age[a] = elapsed / hazard;
  } else {
    exposure[a] = 0.0f;
    exposure_threshold[a] = INFINITY;
    age[a] = 0.0f;
  }
}

#endif /* PHYSARUM_AGENTS_CL */
