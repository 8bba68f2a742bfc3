/* Agent turnover (paper Sec. 3.2, Fig. 2d, hazard form of Sec. 3.3; mirrors reference/turnover.cpp):
 * exposure grows by dt times the hazard 1/tau at the agent's position; at the threshold the agent
 * is reborn uniformly on the surface with a random heading, age and exposure 0 and a fresh
 * Exp(1) threshold. */
#ifndef PHYSARUM_TURNOVER_CL
#define PHYSARUM_TURNOVER_CL
#include "agents.cl"

typedef struct {
  int face;
  float2 position, heading;
  float age, exposure, exposure_threshold, time_since_decision, accumulated_turn;
} AgentState;

void respawn_agent(__global const PhysarumFaceRecord* faces, __global const float* alias_probability,
                   __global const int* alias_index, __global const int* device_face, const int face_count, const uint seed, const uint step,
                   const uint agent, AgentState* s) {
  const FacePoint p = sample_surface_point(faces, alias_probability, alias_index, device_face, face_count,
                                           agent_random_words(seed, agent, step, PHYSARUM_PURPOSE_RESPAWN_PLACEMENT, 0u),
                                           agent_random_words(seed, agent, step, PHYSARUM_PURPOSE_RESPAWN_PLACEMENT, 1u));
  const uint4 state = agent_random_words(seed, agent, step, PHYSARUM_PURPOSE_RESPAWN_STATE, 0u);
  s->face = p.face;
  s->position = p.position;
  s->heading = heading_from_uniform(first_uniform(state));
  s->age = 0.0f;
  s->exposure = 0.0f;
  s->exposure_threshold = exponential_exposure(second_uniform(state));
  s->time_since_decision = 0.0f;
  s->accumulated_turn = 0.0f;
}

/* Ages the agent by dt and respawns it when its exposure reaches the threshold; returns 1 then. */
int advance_turnover(__global const PhysarumFaceRecord* faces, __global const float* alias_probability,
                     __global const int* alias_index, __global const int* device_face, const int face_count, const float hazard, const float dt,
                     const uint seed, const uint step, const uint agent, AgentState* s) {
  s->age += dt;
  if (hazard == 0.0f) return 0;
  s->exposure += dt * hazard;
  if (s->exposure < s->exposure_threshold) return 0;
  respawn_agent(faces, alias_probability, alias_index, device_face, face_count, seed, step, agent, s);
  return 1;
}

#endif /* PHYSARUM_TURNOVER_CL */
