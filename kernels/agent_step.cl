/* One agent step of the extended slime-mold model (mirrors the agent half of
 * reference/simulation.cpp): every agent, independently,
 *   1. senses and steers (sensing_steering.cl) on the field of the previous step,
 *   2. moves, reflecting at boundaries, depositing along its path (movement.cl, deposition.cl),
 *   3. ages and turns over (turnover.cl).
 * One work-item per agent. Rates are read where the step starts, the hazard where it ends, as in
 * the reference. Counters (crossings, reflections, respawns) are summed per work-group in local
 * memory and added to that group's own slot, so no global atomics are spent on them. */
#include "device_types.h"
#include "agents.cl"
#include "deposition.cl"
#include "movement.cl"
#include "sensing_steering.cl"
#include "turnover.cl"
#include "agent_order.cl"

__kernel void agent_step(const PhysarumStepConstants k, __global const PhysarumFaceRecord* faces,
                         __global const PhysarumAgentParameters* vertex_parameters,
                         __global const float* concentration, __global const float* alias_probability,
                         __global const int* alias_index, __global const int* device_face,
                         __global PhysarumDepositCell* deposits,
                         __global int* face, __global float2* position, __global float2* heading,
                         __global float* age, __global float* exposure, __global float* exposure_threshold,
                         __global float* time_since_decision, __global float* accumulated_turn,
                         __global const uint* id, __global ulong* group_counters, __local uint* local_counters) {
  const int a = get_global_id(0);
  const int lid = get_local_id(0);
  if (lid < PHYSARUM_COUNTERS) local_counters[lid] = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);

  /* No early return: every work-item must reach the barriers below. */
  if (a < k.agent_count) {
    const uint agent = id[a];
    AgentState s;
    s.face = face[a];
    s.position = position[a];
    s.heading = heading[a];
    s.age = age[a];
    s.exposure = exposure[a];
    s.exposure_threshold = exposure_threshold[a];
    s.time_since_decision = time_since_decision[a];
    s.accumulated_turn = accumulated_turn[a];

    const PhysarumAgentParameters p = parameters_at(&k, faces, vertex_parameters, s.face, s.position);
    int sensor_crossings = 0;
    sense_and_steer(faces, concentration, &p, k.dt, k.seed, k.step, agent, s.face, s.position, &s.heading,
                    &s.time_since_decision, &s.accumulated_turn, &sensor_crossings);

    const float deposit = p.deposit_rate * k.dt * active_fraction(s.age, k.dt, p.activation_time);
    const TraceEnd moved =
        move_agent(faces, s.face, s.position, s.heading, p.move_rate * k.dt, deposit, deposits, k.deposit_scale);
    s.face = moved.face;
    s.position = moved.position;
    s.heading = moved.heading;

    const float hazard = k.uniform_parameters
                             ? k.uniform.hazard_rate
                             : parameters_at(&k, faces, vertex_parameters, s.face, s.position).hazard_rate;
    const int respawned = advance_turnover(faces, alias_probability, alias_index, device_face, k.face_count, hazard,
                                           k.dt, k.seed, k.step, agent, &s);

    face[a] = s.face;
    position[a] = s.position;
    heading[a] = s.heading;
    age[a] = s.age;
    exposure[a] = s.exposure;
    exposure_threshold[a] = s.exposure_threshold;
    time_since_decision[a] = s.time_since_decision;
    accumulated_turn[a] = s.accumulated_turn;

    if (moved.face_crossings) atomic_add(&local_counters[PHYSARUM_COUNTER_MOVE_CROSSINGS], (uint)moved.face_crossings);
    if (sensor_crossings) atomic_add(&local_counters[PHYSARUM_COUNTER_SENSOR_CROSSINGS], (uint)sensor_crossings);
    if (moved.hit_boundary) atomic_inc(&local_counters[PHYSARUM_COUNTER_BOUNDARY_HITS]);
    if (respawned) atomic_inc(&local_counters[PHYSARUM_COUNTER_RESPAWNS]);
  }

  barrier(CLK_LOCAL_MEM_FENCE);
  if (lid < PHYSARUM_COUNTERS) group_counters[get_group_id(0) * PHYSARUM_COUNTERS + lid] += local_counters[lid];
}

/* The step's deposits into the field: u_i += amount_i / m_i, and the accumulator cleared for the
 * next step (mirrors ReferencePheromone::add_deposits). */
__kernel void deposits_to_concentration(const int n, __global PhysarumDepositCell* deposits,
                                        __global const float* inverse_mass, const float inverse_scale,
                                        __global float* concentration) {
  const int i = get_global_id(0);
  if (i >= n) return;
#ifdef PHYSARUM_FLOAT_DEPOSITS
  const float amount = deposits[i];
  deposits[i] = 0.0f;
#else
  const float amount = convert_float(deposits[i]) * inverse_scale;
  deposits[i] = 0;
#endif
  concentration[i] += amount * inverse_mass[i];
}
