#include "reference/sensing_steering.hpp"

#include "common/model/domain_sampling.hpp"
#include "common/base/random_streams.hpp"
#include "common/surface/trace.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {

double read_sensor(const SurfaceDomain& domain, const IntrinsicVertexData<double>& concentration, int face,
                   const Eigen::Vector2d& position, const Eigen::Vector2d& direction, double distance,
                   long long* crossings, const IntrinsicVertexData<double>* stimulus) {
  const TraceResult end = trace(domain, face, position, direction, distance, BoundaryRule::Stop);
  if (crossings) *crossings += end.face_crossings;
  if (end.hit_boundary) return 0.0;
  const double pheromone = interpolate_vertex_field(domain, concentration, end.face, end.position);
  if (!stimulus) return pheromone;
  return pheromone + interpolate_vertex_field(domain, *stimulus, end.face, end.position);
}

Eigen::Vector2d rotate(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

SensorReadings read_sensors(const SurfaceDomain& domain, const IntrinsicVertexData<double>& concentration, int face,
                            const Eigen::Vector2d& position, const Eigen::Vector2d& heading, double sensor_angle,
                            double sensor_distance, long long* crossings, const IntrinsicVertexData<double>* stimulus) {
  SensorReadings r;
  r.left = read_sensor(domain, concentration, face, position, rotate(heading, sensor_angle), sensor_distance, crossings,
                       stimulus);
  r.centre = read_sensor(domain, concentration, face, position, heading, sensor_distance, crossings, stimulus);
  r.right = read_sensor(domain, concentration, face, position, rotate(heading, -sensor_angle), sensor_distance,
                        crossings, stimulus);
  return r;
}

TurnChoice jones_turn_choice(const SensorReadings& r) {
  if (r.centre > r.left && r.centre > r.right) return TurnChoice::Straight;
  if (r.centre < r.left && r.centre < r.right) return TurnChoice::RandomSide;
  if (r.left > r.right) return TurnChoice::Left;
  if (r.right > r.left) return TurnChoice::Right;
  return TurnChoice::Straight;
}

void sense_and_steer(const SurfaceDomain& domain, const VertexParameters& params, const IntrinsicVertexData<double>& concentration,
                     double dt, std::uint32_t seed, std::uint32_t step, Agents& agents, long long* sensor_crossings,
                     const IntrinsicVertexData<double>* stimulus, AgentRange range) {
  const int end = std::min(range.end, agents.count());
  for (int a = range.begin; a < end; ++a) {
    const int face = agents.face[a];
    const Eigen::Vector2d& position = agents.position[a];
    const double turn_rate = interpolate_vertex_field(domain, params[Param::turn_rate], face, position);
    const double period = 1.0 / interpolate_vertex_field(domain, params[Param::turn_frequency], face, position);
    agents.time_since_decision[a] += dt;
    agents.accumulated_turn[a] += turn_rate * dt;
    // A decision is due once a full period has elapsed. The clock is a sum of many dt, so allow a
    // rounding-sized shortfall: otherwise a period of exactly 5 dt could be missed by 1e-17 s and
    // the decision slip a whole step late. 1e-4 dt covers float32 rounding too, so the OpenCL
    // backend (kernels/sensing_steering.cl) uses the same tolerance and both decide alike from the
    // same state; a decision at most 1e-4 dt early changes nothing measurable.
    const double tolerance = kTurnDecisionTolerance * dt;
    if (agents.time_since_decision[a] + tolerance < period) continue;

    const double sensor_angle = interpolate_vertex_field(domain, params[Param::sensor_angle], face, position);
    const double sensor_distance = interpolate_vertex_field(domain, params[Param::sensor_distance], face, position);
    PhiloxWords side_bits{};
    bool side_bits_drawn = false;
    for (int k = 0; k < kMaxTurnDecisionsPerStep && agents.time_since_decision[a] + tolerance >= period; ++k) {
      // The decision happens `overshoot` seconds before the step's end: the turn accumulated during
      // the overshoot belongs to the next period.
      const double overshoot = std::max(agents.time_since_decision[a] - period, 0.0);
      const double carried_turn = turn_rate * overshoot;
      const double magnitude = agents.accumulated_turn[a] - carried_turn;
      agents.time_since_decision[a] = overshoot;
      agents.accumulated_turn[a] = carried_turn;

      const SensorReadings readings = read_sensors(domain, concentration, face, position, agents.heading[a],
                                                   sensor_angle, sensor_distance, sensor_crossings, stimulus);
      TurnChoice choice = jones_turn_choice(readings);
      if (choice == TurnChoice::RandomSide) {
        if (!side_bits_drawn) {
          side_bits = agent_random_words(seed, static_cast<std::uint32_t>(a), step, RandomPurpose::TurnDirection);
          side_bits_drawn = true;
        }
        choice = (side_bits[k] >> 31) == 0 ? TurnChoice::Left : TurnChoice::Right;
      }
      if (choice == TurnChoice::Left) agents.heading[a] = rotate(agents.heading[a], magnitude).normalized();
      if (choice == TurnChoice::Right) agents.heading[a] = rotate(agents.heading[a], -magnitude).normalized();
    }
    // More decisions were due than one step may take (dt > kMaxTurnDecisionsPerStep periods): drop
    // the backlog rather than let it grow without bound.
    if (agents.time_since_decision[a] >= period) {
      agents.time_since_decision[a] = std::fmod(agents.time_since_decision[a], period);
      agents.accumulated_turn[a] = turn_rate * agents.time_since_decision[a];
    }
  }
}

}  // namespace physarum
