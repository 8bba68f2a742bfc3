/* One agent step of the extended slime-mold model (mirrors the agent half of
 * reference/agent_simulation.cpp): every agent, independently,
 *   1. steers (sensing_steering.cl) by what it sensed on the field of the previous step (sensed
 *      ahead of this kernel by sense_deciders, for the agents with a decision due), then turns
 *      toward the bias direction (bias.cl, PHYSARUM_BIAS),
 *   2. moves, reflecting at boundaries (or stopping there, PHYSARUM_BOUNDARY_TERMINATE),
 *      depositing along its path (movement.cl, deposition.cl),
 *   3. ages and turns over (turnover.cl): also at once in a sink face or at a terminating boundary.
 * The controls of Sec. 3.3 are build options (opencl/agent_simulation.cpp): a scene without them
 * compiles none of their code, and their buffers are then one-element placeholders never read.
 * Several agents per work-item (walkers of PHYSARUM_AGENTS_PER_WORK_ITEM lanes, below). Rates are
 * read where the step starts, the hazard where it ends, as in the reference. Counters (crossings,
 * reflections, respawns) are summed per work-group in local memory and added to that group's own
 * slot, so no global atomics are spent on them.
 * Competing species (PHYSARUM_SPECIES, species.cl): each agent reads its own species' parameters
 * and sensed field and deposits into its species' cells; `concentration` is then the sensed fields
 * of every species, `vertex_parameters` and `deposits` every species' records and cells. */
#include "device_types.h"
#include "agents.cl"
#include "bias.cl"
#include "deposition.cl"
#include "movement.cl"
#include "sensing_steering.cl"
#include "turnover.cl"
#include "agent_order.cl"
#include "species.cl"

/* Agents per walker (1..4, a build option the host sets) and walkers per work-item
 * (PHYSARUM_MOVE_WALKERS, movement.cl): on a CPU the agents of one walker move in lockstep, one vector
 * lane each, and several walkers take turns, which overlaps their chains of face reads; a GPU
 * overlaps them across its threads instead and takes 1 and 1. Results do not depend on either. */
#ifndef PHYSARUM_AGENTS_PER_WORK_ITEM
#define PHYSARUM_AGENTS_PER_WORK_ITEM 1
#endif
#if PHYSARUM_AGENTS_PER_WORK_ITEM < 1 || PHYSARUM_AGENTS_PER_WORK_ITEM > 4
#error "PHYSARUM_AGENTS_PER_WORK_ITEM must be 1, 2, 3 or 4"
#endif
#if PHYSARUM_AGENTS_PER_WORK_ITEM > PHYSARUM_WALK_LANES
#error "PHYSARUM_AGENTS_PER_WORK_ITEM exceeds PHYSARUM_WALK_LANES (lanes.h)"
#endif
#define LANES PHYSARUM_AGENTS_PER_WORK_ITEM
#define AGENTS (PHYSARUM_AGENTS_PER_WORK_ITEM * PHYSARUM_MOVE_WALKERS)

__kernel void agent_step(const PhysarumStepConstants k, __global const PhysarumFaceRecord* faces,
                         __global const PhysarumAgentParameters* vertex_parameters,
                         __global const float* concentration, __global const float* read_stimulus,
                         __global const float* alias_probability, __global const int* alias_index,
                         __global const float* spawn_alias_probability, __global const int* spawn_alias_index,
                         __global const float* spawn_weight, __global const float2* bias_direction,
                         __global const float* bias_strength, __global const int* device_face,
                         __global PhysarumDepositCell* deposits,
                         __global int* face, __global float2* position, __global float2* heading,
                         __global float* age, __global float* exposure, __global float* exposure_threshold,
                         __global float* time_since_decision, __global float* accumulated_turn,
                         __global const uint* id, __global const uint* first_sensing, __global ulong* group_counters,
                         __local uint* local_counters) {
  const int first = get_global_id(0) * AGENTS;
  const int lid = get_local_id(0);
  if (lid < PHYSARUM_COUNTERS) local_counters[lid] = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);

  /* No early return: every work-item must reach the barriers below. */
  AgentState s[AGENTS];
  lane_int active[PHYSARUM_MOVE_WALKERS], start_face[PHYSARUM_MOVE_WALKERS];
  lane_float px[PHYSARUM_MOVE_WALKERS], py[PHYSARUM_MOVE_WALKERS], dx[PHYSARUM_MOVE_WALKERS];
  lane_float dy[PHYSARUM_MOVE_WALKERS], distance[PHYSARUM_MOVE_WALKERS], deposit[PHYSARUM_MOVE_WALKERS];
  for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h) {
    active[h] = start_face[h] = (lane_int)(0);
    px[h] = py[h] = dx[h] = dy[h] = distance[h] = deposit[h] = (lane_float)(0.0f);
  }
#ifdef PHYSARUM_SPECIES
  lane_int cell_offset[PHYSARUM_MOVE_WALKERS];
  for (int h = 0; h < PHYSARUM_MOVE_WALKERS; ++h) cell_offset[h] = (lane_int)(0);
#endif
  uint sensor_crossings = 0u;
#if defined(PHYSARUM_BIAS) && defined(PHYSARUM_BIAS_UNIFORM_STRENGTH)
  /* one strength everywhere (the host uploads just that value): one fraction for every agent */
  const float uniform_bias_fraction = bias_strength[0] > 0.0f ? relaxed_fraction(bias_strength[0] * k.dt) : 0.0f;
#endif
  for (int i = 0; i < AGENTS; ++i) {
    const int a = first + i;
    if (a >= k.agent_count) continue;
    s[i].face = face[a];
    s[i].position = position[a];
    s[i].heading = heading[a];
    s[i].age = age[a];
    s[i].exposure = exposure[a];
    s[i].exposure_threshold = exposure_threshold[a];
    s[i].time_since_decision = time_since_decision[a];
    s[i].accumulated_turn = accumulated_turn[a];

#ifdef PHYSARUM_SPECIES
    __global const PhysarumAgentParameters* own_parameters = species_parameters(vertex_parameters, id[a]);
    __global const float* own_concentration = species_sensed(concentration, id[a]);
#else
    __global const PhysarumAgentParameters* own_parameters = vertex_parameters;
    __global const float* own_concentration = concentration;
#endif
    PhysarumAgentParameters p;
    parameters_at(&k, faces, own_parameters, s[i].face, s[i].position, &p);
    int crossings = 0;
    sense_and_steer(faces, own_concentration, read_stimulus, &p, k.dt, k.seed, k.step, id[a], s[i].face, s[i].position,
                    first_sensing[a], &s[i].heading, &s[i].time_since_decision, &s[i].accumulated_turn, &crossings);
    sensor_crossings += (uint)crossings;
#if defined(PHYSARUM_BIAS) && defined(PHYSARUM_BIAS_UNIFORM_STRENGTH)
    s[i].heading = heading_relaxed_toward(bias_direction[s[i].face], uniform_bias_fraction, s[i].heading);
#elif defined(PHYSARUM_BIAS)
    s[i].heading = biased_heading(faces, bias_direction, bias_strength, s[i].face, s[i].position, s[i].heading, k.dt);
#else
    (void)bias_strength;
#endif

    const int h = i / LANES, lane = i % LANES;
    active[h] = with_lane_int(active[h], lane, -1);
    start_face[h] = with_lane_int(start_face[h], lane, s[i].face);
#ifdef PHYSARUM_SPECIES
    cell_offset[h] = with_lane_int(cell_offset[h], lane, species_cells(id[a]));
#endif
    px[h] = with_lane(px[h], lane, s[i].position.x);
    py[h] = with_lane(py[h], lane, s[i].position.y);
    dx[h] = with_lane(dx[h], lane, s[i].heading.x);
    dy[h] = with_lane(dy[h], lane, s[i].heading.y);
    distance[h] = with_lane(distance[h], lane, p.move_rate * k.dt);
    deposit[h] =
        with_lane(deposit[h], lane, p.deposit_rate * k.dt * active_fraction(s[i].age, k.dt, p.activation_time));
  }

  TraceEnd moved[AGENTS];
  /* Agents fill the walkers in order: when the first walker has none, no walker has any. */
  if (LANE_ANY(active[0]))
    move_agents(faces, LANES, start_face, px, py, dx, dy, distance, deposit, active, deposits, k.deposit_scale,
                moved PHYSARUM_SPECIES_CELL_OFFSETS(cell_offset));

  const SpawnSources spawn = {alias_probability, alias_index, spawn_alias_probability, spawn_alias_index,
                              spawn_weight, bias_direction, device_face, k.face_count};
  uint move_crossings = 0u, boundary_hits = 0u, respawns = 0u;
  for (int i = 0; i < AGENTS; ++i) {
    const int a = first + i;
    if (a >= k.agent_count) continue;
    s[i].face = moved[i].face;
    s[i].position = moved[i].position;
    s[i].heading = moved[i].heading;

    PhysarumAgentParameters here;
#ifdef PHYSARUM_SPECIES
    parameters_at(&k, faces, species_parameters(vertex_parameters, id[a]), s[i].face, s[i].position, &here);
#else
    parameters_at(&k, faces, vertex_parameters, s[i].face, s[i].position, &here);
#endif
    const float hazard = here.hazard_rate;
#ifdef PHYSARUM_BOUNDARY_TERMINATE
    const int removed = moved[i].hit_boundary; /* the walk stopped there (movement.cl): respawn now */
#else
    const int removed = 0;
#endif
    respawns += (uint)advance_turnover(faces, &spawn, hazard, k.dt, k.seed, k.step, id[a], removed, &s[i]);

    face[a] = s[i].face;
    position[a] = s[i].position;
    heading[a] = s[i].heading;
    age[a] = s[i].age;
    exposure[a] = s[i].exposure;
    exposure_threshold[a] = s[i].exposure_threshold;
    time_since_decision[a] = s[i].time_since_decision;
    accumulated_turn[a] = s[i].accumulated_turn;
    move_crossings += (uint)moved[i].face_crossings;
    boundary_hits += (uint)moved[i].hit_boundary;
  }

  if (move_crossings) atomic_add(&local_counters[PHYSARUM_COUNTER_MOVE_CROSSINGS], move_crossings);
  if (sensor_crossings) atomic_add(&local_counters[PHYSARUM_COUNTER_SENSOR_CROSSINGS], sensor_crossings);
  if (boundary_hits) atomic_add(&local_counters[PHYSARUM_COUNTER_BOUNDARY_HITS], boundary_hits);
  if (respawns) atomic_add(&local_counters[PHYSARUM_COUNTER_RESPAWNS], respawns);

  barrier(CLK_LOCAL_MEM_FENCE);
  if (lid < PHYSARUM_COUNTERS) group_counters[get_group_id(0) * PHYSARUM_COUNTERS + lid] += local_counters[lid];
}
