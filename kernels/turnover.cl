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

/* Where newborns appear and which way they face: the alias tables (the domain's, and the spawn
 * distribution's when there are spawn weights or sinks), the spawn weights and the bias directions
 * (read only under the build options that need them, agents.cl). */
typedef struct {
  __global const float* alias_probability;
  __global const int* alias_index;
  __global const float* spawn_alias_probability;
  __global const int* spawn_alias_index;
  __global const float* spawn_weight;
  __global const float2* bias_direction;
  __global const int* device_face;
  int face_count;
} SpawnSources;

void respawn_agent(__global const PhysarumFaceRecord* faces, const SpawnSources* spawn, const uint seed,
                   const uint step, const uint agent, AgentState* s) {
  const FacePoint p = spawn_point(faces, spawn->alias_probability, spawn->alias_index, spawn->spawn_alias_probability,
                                  spawn->spawn_alias_index, spawn->spawn_weight, spawn->device_face, spawn->face_count,
                                  seed, agent, step, PHYSARUM_PURPOSE_RESPAWN_PLACEMENT,
                                  PHYSARUM_PURPOSE_RESPAWN_CORNER);
  const uint4 state = agent_random_words(seed, agent, step, PHYSARUM_PURPOSE_RESPAWN_STATE, 0u);
  s->face = p.face;
  s->position = p.position;
  s->heading = spawn_heading(spawn->bias_direction, p.face, first_uniform(state));
  s->age = 0.0f;
  s->exposure = 0.0f;
  s->exposure_threshold = exponential_exposure(second_uniform(state));
  s->time_since_decision = 0.0f;
  s->accumulated_turn = 0.0f;
}

/* Ages the agent by dt and respawns it when its exposure reaches the threshold, or at once when
 * `removed` (a terminating boundary); returns 1 then. In a sink face (a corner with hazard
 * +infinity: mean lifetime 0) the hazard is +infinity or NaN (0 x infinity), and either makes the
 * exposure test below fail, so the agent goes, as in the reference. */
int advance_turnover(__global const PhysarumFaceRecord* faces, const SpawnSources* spawn, const float hazard,
                     const float dt, const uint seed, const uint step, const uint agent, const int removed,
                     AgentState* s) {
  s->age += dt;
  if (!removed) {
    if (hazard == 0.0f) return 0;
    s->exposure += dt * hazard;
    if (s->exposure < s->exposure_threshold) return 0;
  }
  respawn_agent(faces, spawn, seed, step, agent, s);
  return 1;
}

#endif /* PHYSARUM_TURNOVER_CL */
