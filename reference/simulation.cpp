#include "reference/simulation.hpp"

#include "common/errors.hpp"
#include "reference/deposition.hpp"
#include "reference/movement.hpp"
#include "reference/sensing_steering.hpp"
#include "reference/turnover.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace physarum {

namespace {

const VertexParameters& checked(const SurfaceDomain& domain, const VertexParameters& params,
                                const SimulationSettings& settings) {
  check_simulation_inputs(domain, params, settings, "simulation");
  return params;
}

}  // namespace

ReferenceSimulation::ReferenceSimulation(const SurfaceDomain& domain, VertexParameters params,
                                         const SimulationSettings& settings)
    : domain_(domain),
      params_(checked(domain, params, settings)),
      settings_(settings),
      hazard_rate_(hazard_rate_per_vertex(params_.mean_lifetime)),
      agents_(initialise_agents(domain_, hazard_rate_, params_.turn_frequency, params_.turn_rate, settings.agents,
                                settings.seed)),
      pheromone_(domain_, params_, settings.integrator, settings.time_step),
      deposit_amount_(static_cast<size_t>(domain.vertex_count), 0.0) {
  segments_.reserve(64);
}

ReferenceSimulation::ReferenceSimulation(const SurfaceDomain& domain, const Scene& scene)
    : ReferenceSimulation(domain, VertexParameters::constant(scene, domain.vertex_count), simulation_settings(scene)) {}

void ReferenceSimulation::move_and_deposit() {
  const double dt = settings_.time_step;
  for (int a = 0; a < agents_.count(); ++a) {
    // Rates are read where the step starts.
    const int face = agents_.face[a];
    const Eigen::Vector2d start = agents_.position[a];
    const double move_rate = interpolate_vertex_field(domain_, params_.move_rate, face, start);
    const double activation_time = interpolate_vertex_field(domain_, params_.activation_time, face, start);
    const double deposit =
        interpolate_vertex_field(domain_, params_.deposit_rate, face, start) * dt * active_fraction(agents_.age[a], dt, activation_time);

    const TraceResult r = move_agent(domain_, agents_, a, move_rate * dt, segments_);
    counters_.face_crossings += r.face_crossings;
    counters_.boundary_hits += r.hit_boundary ? 1 : 0;
    deposit_along_path(domain_, segments_, deposit, face, start, deposit_amount_);
  }
}

void ReferenceSimulation::step() {
  const double dt = settings_.time_step;
  const auto step_index = static_cast<std::uint32_t>(steps_taken_);

  sense_and_steer(domain_, params_, pheromone_.concentration(), dt, settings_.seed, step_index, agents_,
                  &counters_.sensor_face_crossings);
  std::fill(deposit_amount_.begin(), deposit_amount_.end(), 0.0);
  move_and_deposit();
  counters_.respawns += advance_turnover(domain_, hazard_rate_, dt, settings_.seed, step_index, agents_);

  // The deposits are the explicit (forward) or implicit (backward) source term; see the header.
  if (settings_.integrator == Integrator::ForwardEuler) {
    pheromone_.step();
    pheromone_.add_deposits(deposit_amount_);
  } else {
    pheromone_.add_deposits(deposit_amount_);
    pheromone_.step();
  }

  counters_.agent_steps += agents_.count();
  ++steps_taken_;
  // Time as steps * dt rather than a running sum, so long runs do not drift.
  time_ = static_cast<double>(steps_taken_) * dt;
}

FieldStatistics ReferenceSimulation::field_statistics(double U) const {
  return compute_field_statistics(pheromone_.concentration(), domain_.vertex_mass, U);
}

}  // namespace physarum
