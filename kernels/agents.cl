/* The agent population on the device (mirrors reference/agents.cpp): random streams, parameter
 * interpolation, uniform points on the surface, and the initial state. Agent state lives in
 * structure-of-arrays buffers, one array per attribute, in the order of reference/agents.hpp. Each
 * agent also carries its id: the key of its random streams, so the numbers it draws do not depend
 * on where it sits in the arrays (agents are reordered by face for memory locality). */
#ifndef PHYSARUM_AGENTS_CL
#define PHYSARUM_AGENTS_CL
#include "device_types.h"
#include <Random123/philox.h>

/* ---- random numbers: the packing of common/philox.hpp and common/random_streams.hpp ---- */

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

PhysarumAgentParameters blend_parameters(const PhysarumAgentParameters a, const PhysarumAgentParameters b,
                                         const PhysarumAgentParameters c, const float3 w) {
  PhysarumAgentParameters r;
  PHYSARUM_BLEND_AGENT_PARAMETERS(r, a, b, c, w)
  return r;
}

/* Every agent parameter at a point (paper Sec. 3.3: maps live at vertices and are interpolated).
 * A uniform scene reads no per-vertex memory at all. */
PhysarumAgentParameters parameters_at(const PhysarumStepConstants* k, __global const PhysarumFaceRecord* faces,
                                      __global const PhysarumAgentParameters* vertex_parameters, const int face,
                                      const float2 p) {
  if (k->uniform_parameters) return k->uniform;
  return blend_parameters(vertex_parameters[faces[face].vertex[0]], vertex_parameters[faces[face].vertex[1]],
                          vertex_parameters[faces[face].vertex[2]], barycentric_in_face(faces, face, p));
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

float2 heading_from_uniform(const float u) {
  float c;
  const float s = sincos(2.0f * M_PI_F * u, &c);
  return (float2)(c, s);
}

float exponential_exposure(const float u) { return -log(u); }

/* ---- the initial state: reference/agents.hpp explains the steady-state draw ---- */
__kernel void initialise_agents(const PhysarumStepConstants k, __global const PhysarumFaceRecord* faces,
                                __global const PhysarumAgentParameters* vertex_parameters,
                                __global const float* alias_probability, __global const int* alias_index,
                                __global const int* device_face, __global int* face, __global float2* position, __global float2* heading,
                                __global float* age, __global float* exposure, __global float* exposure_threshold,
                                __global float* time_since_decision, __global float* accumulated_turn,
                                __global uint* id) {
  const int a = get_global_id(0);
  if (a >= k.agent_count) return;
  const uint agent = (uint)a;
  const FacePoint p = sample_surface_point(
      faces, alias_probability, alias_index, device_face, k.face_count,
      agent_random_words(k.seed, agent, 0u, PHYSARUM_PURPOSE_INITIAL_PLACEMENT, 0u),
      agent_random_words(k.seed, agent, 0u, PHYSARUM_PURPOSE_INITIAL_PLACEMENT, 1u));
  const uint4 state = agent_random_words(k.seed, agent, 0u, PHYSARUM_PURPOSE_INITIAL_STATE, 0u);
  face[a] = p.face;
  position[a] = p.position;
  heading[a] = heading_from_uniform(first_uniform(state));
  id[a] = agent;
  const PhysarumAgentParameters here = parameters_at(&k, faces, vertex_parameters, p.face, p.position);
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
