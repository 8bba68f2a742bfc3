/* Sensing and steering (paper Sec. 3.2, Fig. 2b, Jones' rule; mirrors reference/sensing_steering.cpp).
 * Three sensors at distance d along -theta, 0, +theta read the pheromone at the end of a trace that
 * STOPS at boundaries (a sensor past the boundary reads 0); turn decisions happen at the fixed
 * frequency f, turning by the turn rate integrated over exactly one decision period. */
#ifndef PHYSARUM_SENSING_STEERING_CL
#define PHYSARUM_SENSING_STEERING_CL
#include "device_types.h"
#include "agents.cl"
#include "trace.cl"
#include "species.cl"

/* What the sensed field holds at vertex v: the pheromone, plus the read-stimulus (Sec. 3.3) when
 * the controls have one (PHYSARUM_READ_STIMULUS; otherwise that buffer is never read). */
float sensed_value(__global const float* concentration, __global const float* read_stimulus, const int v) {
#ifdef PHYSARUM_READ_STIMULUS
#ifdef PHYSARUM_FAULT_STIMULUS_SIGN
  return concentration[v] - read_stimulus[v]; /* planted fault: the read-stimulus weight negated */
#else
  return concentration[v] + read_stimulus[v];
#endif
#else
  (void)read_stimulus;
  return concentration[v];
#endif
}

/* The sensed field at barycentric point b of `face`, interpolated from its corners. */
float reading_at(__global const PhysarumFaceRecord* faces, __global const float* concentration,
                 __global const float* read_stimulus, const int face, const float3 b) {
  return b.x * sensed_value(concentration, read_stimulus, faces[face].vertex[0]) +
         b.y * sensed_value(concentration, read_stimulus, faces[face].vertex[1]) +
         b.z * sensed_value(concentration, read_stimulus, faces[face].vertex[2]);
}

/* What a sensor reads: the pheromone at its trace's end; 0 when the trace met the boundary (a
 * sensor past the boundary reads nothing). */
float sensor_reading(__global const PhysarumFaceRecord* faces, __global const float* concentration,
                     __global const float* read_stimulus, const TraceEnd* end) {
  return end->hit_boundary ? 0.0f : reading_at(faces, concentration, read_stimulus, end->face, end->barycentric);
}

float2 rotate(const float2 v, const float angle) {
  float c;
  const float s = sincos(angle, &c);
  return (float2)(c * v.x - s * v.y, s * v.x + c * v.y);
}

/* The left and right sensor directions, heading h rotated by +angle and -angle: one sincos for
 * both (sin is odd, so this is rotate(h, -angle) for the right one). */
void sensor_rays(const float2 h, const float angle, float2* left, float2* right) {
  float c;
  const float s = sincos(angle, &c);
  *left = (float2)(c * h.x - s * h.y, s * h.x + c * h.y);
  *right = (float2)(c * h.x + s * h.y, -s * h.x + c * h.y);
}

#define PHYSARUM_TURN_STRAIGHT 0
#define PHYSARUM_TURN_LEFT 1
#define PHYSARUM_TURN_RIGHT 2
#define PHYSARUM_TURN_RANDOM_SIDE 3

/* Jones' rule: centre strongest -> straight; centre weakest -> a random side; otherwise towards the
 * stronger side; a full tie -> straight. */
int jones_turn_choice(const float left, const float centre, const float right) {
  if (centre > left && centre > right) return PHYSARUM_TURN_STRAIGHT;
  if (centre < left && centre < right) return PHYSARUM_TURN_RANDOM_SIDE;
  if (left > right) return PHYSARUM_TURN_LEFT;
  if (right > left) return PHYSARUM_TURN_RIGHT;
  return PHYSARUM_TURN_STRAIGHT;
}

/* The time between turn decisions (s). */
float decision_period(const PhysarumAgentParameters* p, const float dt) {
#ifdef PHYSARUM_FAULT_TURN_EVERY_STEP
  return dt; /* planted fault: decisions ignore the decision frequency */
#else
  return 1.0f / p->turn_frequency;
#endif
}

/* Whether a decision is due once the decision clock reads `clock`. The clock is a float sum of dt,
 * so a decision due at a whole number of steps may arrive a few float ulps short of its period; the
 * tolerance (PHYSARUM_TURN_DECISION_TOLERANCE dt, far above float rounding and far below any
 * meaningful time) keeps it on time. The reference uses the same tolerance, so both decide alike
 * from one state; collect_deciders and sense_and_steer both ask here, so they agree to the bit. */
int decision_due(const float clock, const float dt, const float period) {
  const float tolerance = PHYSARUM_TURN_DECISION_TOLERANCE * dt;
  return clock + tolerance >= period;
}

float sensor_angle_of(const PhysarumAgentParameters* p) {
#ifdef PHYSARUM_FAULT_SENSOR_ANGLE
  return 1.15f * p->sensor_angle; /* planted fault: the sensor angle 15 % too wide */
#else
  return p->sensor_angle;
#endif
}

/* One sensing of one agent: its three sensor traces, read and compared by Jones' rule. */
int sense_turn_choice(__global const PhysarumFaceRecord* faces, __global const float* concentration,
                      __global const float* read_stimulus, const PhysarumAgentParameters* p, const int face, const float2 position, const float2 heading,
                      int* sensor_crossings) {
  const float sensor_angle = sensor_angle_of(p);
  TraceEnd left_end, centre_end, right_end;
  float2 left, right;
  sensor_rays(heading, sensor_angle, &left, &right);
  trace_three_sensors(faces, face, position, left, heading, right, p->sensor_distance, &left_end, &centre_end,
                      &right_end);
  *sensor_crossings += left_end.face_crossings + centre_end.face_crossings + right_end.face_crossings;
  return jones_turn_choice(sensor_reading(faces, concentration, read_stimulus, &left_end),
                           sensor_reading(faces, concentration, read_stimulus, &centre_end),
                           sensor_reading(faces, concentration, read_stimulus, &right_end));
}

/* A sensing done ahead of the agent step (sense_deciders, below): the turn choice in the low two
 * bits, the face crossings of its three traces above them. */
uint pack_sensing(const int choice, const int crossings) { return (uint)choice | ((uint)crossings << 2); }
int sensing_choice(const uint packed) { return (int)(packed & 3u); }
int sensing_crossings(const uint packed) { return (int)(packed >> 2); }

/* Steers one agent for one step of length dt. The step's first sensing (if a decision is due) was
 * done by sense_deciders and arrives packed in `first_sensing`; a second or later decision in the
 * same step (turn frequency above 1/dt) senses here, from the heading the earlier ones left. */
void sense_and_steer(__global const PhysarumFaceRecord* faces, __global const float* concentration,
                     __global const float* read_stimulus, const PhysarumAgentParameters* p, const float dt, const uint seed, const uint step,
                     const uint agent, const int face, const float2 position, const uint first_sensing,
                     float2* heading, float* time_since_decision, float* accumulated_turn, int* sensor_crossings) {
  const float period = decision_period(p, dt);
  *time_since_decision += dt;
  *accumulated_turn += p->turn_rate * dt;
  if (!decision_due(*time_since_decision, dt, period)) return;

  uint4 side_bits = (uint4)(0u);
  int side_bits_drawn = 0;
  for (int k = 0; k < PHYSARUM_MAX_TURN_DECISIONS_PER_STEP && decision_due(*time_since_decision, dt, period); ++k) {
    const float overshoot = fmax(*time_since_decision - period, 0.0f);
    const float carried_turn = p->turn_rate * overshoot;
    const float magnitude = *accumulated_turn - carried_turn;
    *time_since_decision = overshoot;
    *accumulated_turn = carried_turn;

    int choice;
    if (k == 0) {
      choice = sensing_choice(first_sensing);
      *sensor_crossings += sensing_crossings(first_sensing);
    } else {
      choice = sense_turn_choice(faces, concentration, read_stimulus, p, face, position, *heading, sensor_crossings);
    }
    if (choice == PHYSARUM_TURN_RANDOM_SIDE) {
      if (!side_bits_drawn) {
        side_bits = agent_random_words(seed, agent, step, PHYSARUM_PURPOSE_TURN_DIRECTION, 0u);
        side_bits_drawn = 1;
      }
      const uint word = k == 0 ? side_bits.x : (k == 1 ? side_bits.y : (k == 2 ? side_bits.z : side_bits.w));
      choice = (word >> 31) == 0u ? PHYSARUM_TURN_LEFT : PHYSARUM_TURN_RIGHT;
    }
    if (choice == PHYSARUM_TURN_LEFT) *heading = normalize(rotate(*heading, magnitude));
    if (choice == PHYSARUM_TURN_RIGHT) *heading = normalize(rotate(*heading, -magnitude));
  }
  if (*time_since_decision >= period) {
    *time_since_decision = fmod(*time_since_decision, period);
    *accumulated_turn = p->turn_rate * *time_since_decision;
  }
}

/* ---- Sensing ahead of the agent step ----
 * Sensor traces are most of an agent step's face crossings (ten sensor lengths of travel for each
 * of the three sensors, against one move), yet only the agents with a decision due sense: one in
 * turn_frequency dt. Sensing inside the agent step would leave most vector lanes (CPU) or threads
 * (GPU) idle, and one agent's three traces in flight are too few to hide the latency of their
 * chains of face reads. So the step starts by listing the agents with a decision due
 * (collect_deciders), then senses for exactly those, packed densely (sense_deciders): on a CPU the
 * 15 traces of five agents walk together in the lanes of float16 vectors, several such walkers per
 * work-item taking turns; on a GPU each thread senses for one agent. The agent step then steers
 * with the packed result. With competing species (species.cl) each agent's id picks its species'
 * parameters and sensed field. */

/* Agents sensed per block of a work-item: five per walker (15 traces in 16 lanes) with vector lanes,
 * one without. */
#if PHYSARUM_WALK_LANES == 16
#define PHYSARUM_SENSING_AGENTS_PER_WORK_ITEM (PHYSARUM_SENSING_AGENTS_PER_WALKER * PHYSARUM_SENSING_WALKERS)
#else
#define PHYSARUM_SENSING_AGENTS_PER_WORK_ITEM 1
#endif

/* Appends every agent with a decision due in this step to `deciders` (`decider_count` must be 0
 * before): slots are taken per work-group in local memory, then one global atomic per group. */
__kernel void collect_deciders(const PhysarumStepConstants k, __global const PhysarumFaceRecord* faces,
                               __global const PhysarumAgentParameters* vertex_parameters, __global const int* face,
                               __global const float2* position, __global const float* time_since_decision,
                               __global const uint* id, __global int* deciders, __global uint* decider_count,
                               __local uint* group_slots) {
  const int a = get_global_id(0);
  if (get_local_id(0) == 0) group_slots[0] = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  int slot = -1;
  if (a < k.agent_count) {
    PhysarumAgentParameters p;
#ifdef PHYSARUM_SPECIES
    parameters_at(&k, faces, species_parameters(vertex_parameters, id[a]), face[a], position[a], &p);
#else
    (void)id;
    parameters_at(&k, faces, vertex_parameters, face[a], position[a], &p);
#endif
    if (decision_due(time_since_decision[a] + k.dt, k.dt, decision_period(&p, k.dt)))
      slot = (int)atomic_inc(&group_slots[0]);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (get_local_id(0) == 0) group_slots[1] = atomic_add(decider_count, group_slots[0]);
  barrier(CLK_LOCAL_MEM_FENCE);
  if (slot >= 0) deciders[group_slots[1] + (uint)slot] = a;
}

/* The first sensing of this step for the agents listed in deciders[first .. first + count). */
void sense_listed_agents(const PhysarumStepConstants* k, __global const PhysarumFaceRecord* faces,
                         __global const PhysarumAgentParameters* vertex_parameters, __global const float* concentration,
                         __global const float* read_stimulus, __global const int* face,
                         __global const float2* position, __global const float2* heading, __global const uint* id,
                         __global const int* deciders, const int first, const int count,
                         __global uint* first_sensing) {
#ifndef PHYSARUM_SPECIES
  (void)id;
#endif
#if PHYSARUM_SENSING_AGENTS_PER_WORK_ITEM == 1
  const int a = deciders[first];
  PhysarumAgentParameters p;
#ifdef PHYSARUM_SPECIES
  parameters_at(k, faces, species_parameters(vertex_parameters, id[a]), face[a], position[a], &p);
  __global const float* own_concentration = species_sensed(concentration, id[a]);
#else
  parameters_at(k, faces, vertex_parameters, face[a], position[a], &p);
  __global const float* own_concentration = concentration;
#endif
  int crossings = 0;
  const int choice =
      sense_turn_choice(faces, own_concentration, read_stimulus, &p, face[a], position[a], heading[a], &crossings);
  first_sensing[a] = pack_sensing(choice, crossings);
#else
  /* PHYSARUM_SENSING_WALKERS walkers of 16 lanes, PHYSARUM_SENSING_AGENTS_PER_WALKER (five) agents
   * each: lanes 3j, 3j+1, 3j+2 of walker i / 5 (j = i % 5) are the left, centre and right traces of
   * the i-th listed agent. The walkers take turns step by step and each prefetches the faces it
   * enters (trace.cl), so one walker's face reads arrive while the others compute. */
  lane_int start_face[PHYSARUM_SENSING_WALKERS], active[PHYSARUM_SENSING_WALKERS];
  lane_float px[PHYSARUM_SENSING_WALKERS], py[PHYSARUM_SENSING_WALKERS], dx[PHYSARUM_SENSING_WALKERS];
  lane_float dy[PHYSARUM_SENSING_WALKERS], length[PHYSARUM_SENSING_WALKERS];
  for (int h = 0; h < PHYSARUM_SENSING_WALKERS; ++h) {
    start_face[h] = active[h] = (lane_int)(0);
    px[h] = py[h] = dx[h] = dy[h] = length[h] = (lane_float)(0.0f);
  }
  for (int i = 0; i < count; ++i) {
    const int a = deciders[first + i];
    PhysarumAgentParameters p;
#ifdef PHYSARUM_SPECIES
    parameters_at(k, faces, species_parameters(vertex_parameters, id[a]), face[a], position[a], &p);
#else
    parameters_at(k, faces, vertex_parameters, face[a], position[a], &p);
#endif
    const float sensor_angle = sensor_angle_of(&p);
    float2 ray[3];
    ray[1] = heading[a];
    sensor_rays(ray[1], sensor_angle, &ray[0], &ray[2]);
    const int walker = i / PHYSARUM_SENSING_AGENTS_PER_WALKER;
    for (int r = 0; r < 3; ++r) {
      const int lane = 3 * (i % PHYSARUM_SENSING_AGENTS_PER_WALKER) + r;
      active[walker] = with_lane_int(active[walker], lane, -1);
      start_face[walker] = with_lane_int(start_face[walker], lane, face[a]);
      px[walker] = with_lane(px[walker], lane, position[a].x);
      py[walker] = with_lane(py[walker], lane, position[a].y);
      dx[walker] = with_lane(dx[walker], lane, ray[r].x);
      dy[walker] = with_lane(dy[walker], lane, ray[r].y);
      length[walker] = with_lane(length[walker], lane, p.sensor_distance);
    }
  }
  WalkLanes w[PHYSARUM_SENSING_WALKERS];
#pragma unroll
  for (int h = 0; h < PHYSARUM_SENSING_WALKERS; ++h)
    w[h] = walk_lanes_start(faces, PHYSARUM_WALK_LANES, start_face[h], px[h], py[h], dx[h], dy[h], length[h], active[h]);
  WalkPieces piece;
  for (int step = 0; step < PHYSARUM_MAX_TRACE_STEPS; ++step) {
    lane_int walking = (lane_int)(0);
#pragma unroll
    for (int h = 0; h < PHYSARUM_SENSING_WALKERS; ++h) {
      if (LANE_ANY(w[h].walking)) walk_lanes_step(faces, PHYSARUM_WALK_LANES, &w[h], 0, &piece);
      walking |= w[h].walking;
    }
    if (!LANE_ANY(walking)) break;
  }
  /* Each trace's end clamped into its face, as walk_lane_ends does, once per walker. */
#pragma unroll
  for (int h = 0; h < PHYSARUM_SENSING_WALKERS; ++h) clamp_barycentric_lanes(&w[h].b0, &w[h].b1, &w[h].b2);
  for (int i = 0; i < count; ++i) {
    const WalkLanes* walker = &w[i / PHYSARUM_SENSING_AGENTS_PER_WALKER];
    const int lane = 3 * (i % PHYSARUM_SENSING_AGENTS_PER_WALKER);
    float reading[3];
    int crossings = 0;
#ifdef PHYSARUM_SPECIES
    __global const float* own_concentration = species_sensed(concentration, id[deciders[first + i]]);
#else
    __global const float* own_concentration = concentration;
#endif
    for (int r = 0; r < 3; ++r) {
      const float3 b = (float3)(float_in_lane(walker->b0, lane + r), float_in_lane(walker->b1, lane + r),
                                float_in_lane(walker->b2, lane + r));
      reading[r] = int_in_lane(walker->hit_boundary, lane + r)
                       ? 0.0f
                       : reading_at(faces, own_concentration, read_stimulus, int_in_lane(walker->face, lane + r), b);
      crossings += int_in_lane(walker->face_crossings, lane + r);
    }
    const int choice = jones_turn_choice(reading[0], reading[1], reading[2]);
    first_sensing[deciders[first + i]] = pack_sensing(choice, crossings);
  }
#endif
}

/* The first sensing of this step for every listed agent (from its state at the step's start),
 * packed into first_sensing[agent]. The list's length is known only on the device, so the host
 * launches a fixed number of work-groups, enough to fill the device, and each group takes an equal,
 * contiguous share of the list's blocks of PHYSARUM_SENSING_AGENTS_PER_WORK_ITEM agents. Equal:
 * launching one work-item per possible block would leave most of them idle and, where a runtime
 * hands out work-groups in contiguous chunks (PoCL), all the work to the first chunk. Contiguous:
 * the list is in agent order, agents are sorted by face, so a group's traces stay in one region
 * of the surface and its face reads hit the core's own cache (faster than dealing blocks
 * round-robin: bench/README.md, "Tuning measurements"). */
__kernel void sense_deciders(const PhysarumStepConstants k, __global const PhysarumFaceRecord* faces,
                             __global const PhysarumAgentParameters* vertex_parameters,
                             __global const float* concentration, __global const float* read_stimulus,
                             __global const int* face, __global const float2* position,
                             __global const float2* heading, __global const uint* id, __global const int* deciders,
                             __global const uint* decider_count, __global uint* first_sensing) {
  const int count = (int)*decider_count;
  const int per_item = PHYSARUM_SENSING_AGENTS_PER_WORK_ITEM;
  const int blocks = (count + per_item - 1) / per_item;
  const int groups = (int)get_num_groups(0), group = (int)get_group_id(0);
  const int group_first = (int)(((long)blocks * group) / groups);
  const int group_end = (int)(((long)blocks * (group + 1)) / groups);
  for (int b = group_first + (int)get_local_id(0); b < group_end; b += (int)get_local_size(0)) {
    const int first = b * per_item;
    sense_listed_agents(&k, faces, vertex_parameters, concentration, read_stimulus, face, position, heading, id,
                        deciders, first, min(count - first, per_item), first_sensing);
  }
}

#endif /* PHYSARUM_SENSING_STEERING_CL */
