/* Sensing and steering (paper Sec. 3.2, Fig. 2b, Jones' rule; mirrors reference/sensing_steering.cpp).
 * Three sensors at distance d along -theta, 0, +theta read the pheromone at the end of a trace that
 * STOPS at boundaries (a sensor past the boundary reads 0); turn decisions happen at the fixed
 * frequency f, turning by the turn rate integrated over exactly one decision period. */
#ifndef PHYSARUM_SENSING_STEERING_CL
#define PHYSARUM_SENSING_STEERING_CL
#include "device_types.h"
#include "agents.cl"
#include "trace.cl"

/* What a sensor reads: the pheromone at its trace's end, interpolated barycentrically; 0 when the
 * trace met the boundary (a sensor past the boundary reads nothing). */
float sensor_reading(__global const PhysarumFaceRecord* faces, __global const float* concentration,
                     const TraceEnd* end) {
  if (end->hit_boundary) return 0.0f;
  const float3 b = end->barycentric;
  return b.x * concentration[faces[end->face].vertex[0]] + b.y * concentration[faces[end->face].vertex[1]] +
         b.z * concentration[faces[end->face].vertex[2]];
}

float2 rotate(const float2 v, const float angle) {
  float c;
  const float s = sincos(angle, &c);
  return (float2)(c * v.x - s * v.y, s * v.x + c * v.y);
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

/* Steers one agent for one step of length dt. The clock is a float sum of dt, so a decision due
 * at a whole number of steps may arrive a few float ulps short of its period; the tolerance
 * (PHYSARUM_TURN_DECISION_TOLERANCE dt, far above float rounding and far below any meaningful time)
 * keeps it on time. The reference uses the same tolerance, so both decide alike from one state. */
void sense_and_steer(__global const PhysarumFaceRecord* faces, __global const float* concentration,
                     const PhysarumAgentParameters* p, const float dt, const uint seed, const uint step,
                     const uint agent, const int face, const float2 position, float2* heading,
                     float* time_since_decision, float* accumulated_turn, int* sensor_crossings) {
#ifdef PHYSARUM_FAULT_TURN_EVERY_STEP
  const float period = dt; /* planted fault: decisions ignore the decision frequency */
#else
  const float period = 1.0f / p->turn_frequency;
#endif
#ifdef PHYSARUM_FAULT_SENSOR_ANGLE
  const float sensor_angle = 1.15f * p->sensor_angle; /* planted fault: the sensor angle 15 % too wide */
#else
  const float sensor_angle = p->sensor_angle;
#endif
  *time_since_decision += dt;
  *accumulated_turn += p->turn_rate * dt;
  const float tolerance = PHYSARUM_TURN_DECISION_TOLERANCE * dt;
  if (*time_since_decision + tolerance < period) return;

  uint4 side_bits = (uint4)(0u);
  int side_bits_drawn = 0;
  for (int k = 0; k < PHYSARUM_MAX_TURN_DECISIONS_PER_STEP && *time_since_decision + tolerance >= period; ++k) {
    const float overshoot = fmax(*time_since_decision - period, 0.0f);
    const float carried_turn = p->turn_rate * overshoot;
    const float magnitude = *accumulated_turn - carried_turn;
    *time_since_decision = overshoot;
    *accumulated_turn = carried_turn;

    TraceEnd left_end, centre_end, right_end;
    trace_three_sensors(faces, face, position, rotate(*heading, sensor_angle), *heading,
                        rotate(*heading, -sensor_angle), p->sensor_distance, &left_end, &centre_end, &right_end);
    *sensor_crossings += left_end.face_crossings + centre_end.face_crossings + right_end.face_crossings;
    const float left = sensor_reading(faces, concentration, &left_end);
    const float centre = sensor_reading(faces, concentration, &centre_end);
    const float right = sensor_reading(faces, concentration, &right_end);
    int choice = jones_turn_choice(left, centre, right);
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

#endif /* PHYSARUM_SENSING_STEERING_CL */
