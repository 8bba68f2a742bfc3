#pragma once
// Sensing and steering (paper Sec. 3.2, Fig. 2b; Jones' rule [Jon10b]). An agent reads the
// pheromone with three sensors at distance d along the directions -theta, 0, +theta from its
// heading, and turns at the fixed turn-decision frequency f_i by the turn rate omega integrated over
// the decision period (omega / f_i for a constant omega), independently of the time step.
#include "common/surface/surface_domain.hpp"
#include "common/model/vertex_parameters.hpp"
#include "common/model/agent_model.hpp"
#include "common/model/agents.hpp"
#include "common/base/element_data.hpp"

#include <cstdint>
#include <vector>

namespace physarum {

// What one sensor reads: the pheromone at the end of a geodesic trace of length `distance` from
// (face, position) along `direction`, interpolated barycentrically from the vertex concentrations.
// Sensors stop at boundaries (BoundaryRule::Stop), and a sensor whose trace meets the boundary
// reads nothing: 0, so agents are not drawn towards the rim.
// `crossings`, when given, is increased by the faces the trace crossed. `stimulus`, when given (the
// summed read-stimuli of Sec. 3.3, per vertex), is added to what an in-bounds sensor reads,
// interpolated the same way.
double read_sensor(const SurfaceDomain& domain, const IntrinsicVertexData<double>& concentration, int face,
                   const Eigen::Vector2d& position, const Eigen::Vector2d& direction, double distance,
                   long long* crossings = nullptr, const IntrinsicVertexData<double>* stimulus = nullptr);

struct SensorReadings {
  double left = 0.0;    // at +angle (counter-clockwise of the heading)
  double centre = 0.0;
  double right = 0.0;   // at -angle
};

// Reads the three sensors of an agent. A negative sensor_angle swaps the sides, which turns
// attraction into chemo-repulsion (Fig. 9c).
SensorReadings read_sensors(const SurfaceDomain& domain, const IntrinsicVertexData<double>& concentration, int face,
                            const Eigen::Vector2d& position, const Eigen::Vector2d& heading, double sensor_angle,
                            double sensor_distance, long long* crossings = nullptr,
                            const IntrinsicVertexData<double>* stimulus = nullptr);

enum class TurnChoice { Straight, Left, Right, RandomSide };

// Jones' rule: centre strongest -> keep going; centre weakest (both sides beat it) -> a random side;
// otherwise towards the stronger side; a full tie (e.g. no pheromone anywhere) -> keep going.
TurnChoice jones_turn_choice(const SensorReadings& readings);

// Rotates a unit vector by `angle` radians (positive = counter-clockwise = to the agent's left).
Eigen::Vector2d rotate(const Eigen::Vector2d& v, double angle);

// Sensing and steering of every agent for one step of length dt (step index `step`, for the random
// side choice: RandomPurpose::TurnDirection). Each agent's clock and accumulated turn advance by dt
// and omega(x) dt; whenever the clock reaches the decision period 1/f(x) the agent senses and turns by
// the turn accumulated over exactly that period, and the remainder carries to the next period.
// Parameters are interpolated at the agent's position. `sensor_crossings`, when given, is increased
// by the faces the sensor traces crossed; `stimulus` (may be null) is the read-stimulus sensors add.
// Only the agents of `range` (one species, whose `params` these are) are advanced.
void sense_and_steer(const SurfaceDomain& domain, const VertexParameters& params, const IntrinsicVertexData<double>& concentration,
                     double dt, std::uint32_t seed, std::uint32_t step, Agents& agents,
                     long long* sensor_crossings = nullptr, const IntrinsicVertexData<double>* stimulus = nullptr,
                     AgentRange range = {});

}  // namespace physarum
