#include "reference/simulation.hpp"

#include "common/agent_model.hpp"
#include "common/directional_bias.hpp"
#include "common/domain_sampling.hpp"
#include "common/errors.hpp"
#include "reference/agents.hpp"
#include "reference/deposition.hpp"
#include "reference/directional_bias.hpp"
#include "reference/movement.hpp"
#include "reference/sensing_steering.hpp"
#include "reference/turnover.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace physarum {

namespace {

const VertexParameters& checked(const SurfaceDomain& domain, const VertexParameters& params,
                                const SimulationSettings& settings) {
  check_simulation_inputs(domain, params, settings, "simulation");
  return params;
}

// The per-vertex controls (read-stimulus; the write rate is the field model's to check).
const SimulationControls& checked(const SurfaceDomain& domain, const SimulationControls& controls) {
  check_controls(domain, controls, "simulation");
  return controls;
}

}  // namespace

ReferenceSimulation::ReferenceSimulation(const SurfaceDomain& domain, VertexParameters params,
                                         const SimulationSettings& settings)
    : ReferenceSimulation(domain, std::move(params), SimulationControls{}, settings) {}

ReferenceSimulation::ReferenceSimulation(const SurfaceDomain& domain, VertexParameters params,
                                         const SimulationControls& controls, const SimulationSettings& settings)
    : domain_(domain),
      params_(checked(domain, params, settings)),
      controls_(checked(domain, controls)),
      settings_(settings),
      hazard_rate_(hazard_rate_per_vertex(params_[Param::mean_lifetime])),
      spawn_(build_spawn_distribution(domain_, controls_.spawn_weight, hazard_rate_)),
      spawn_rule_{&spawn_, controls_.spawn_heading, controls_.bias ? &*controls_.bias : nullptr},
      agents_(initialise_agents(domain_, hazard_rate_, params_[Param::turn_frequency], params_[Param::turn_rate],
                                settings.agents, settings.seed, spawn_rule_)),
      field_model_(domain_, params_, settings.integrator, settings.time_step),
      layers_(kDynamicLayers, IntrinsicVertexData<double>(static_cast<size_t>(domain.vertex_count), 0.0)),
      deposit_amount_(static_cast<size_t>(domain.vertex_count), 0.0) {
  field_model_.set_write_rate(controls_.write_rate);
  segments_.reserve(64);
  if (controls_.boundary == BoundaryBehaviour::Terminate) terminated_.assign(static_cast<size_t>(settings.agents), 0);
}

ReferenceSimulation::ReferenceSimulation(const SurfaceDomain& domain, const Scene& scene)
    : ReferenceSimulation(domain, VertexParameters::constant(scene.parameters, domain.vertex_count), simulation_settings(scene)) {}

void ReferenceSimulation::move_and_deposit() {
  const double dt = settings_.time_step;
  const bool terminate = controls_.boundary == BoundaryBehaviour::Terminate;
  for (int a = 0; a < agents_.count(); ++a) {
    // Rates are read where the step starts.
    const int face = agents_.face[a];
    const Eigen::Vector2d start = agents_.position[a];
    const double move_rate = interpolate_vertex_field(domain_, params_[Param::move_rate], face, start);
    const double activation_time = interpolate_vertex_field(domain_, params_[Param::activation_time], face, start);
    const double deposit =
        interpolate_vertex_field(domain_, params_[Param::deposit_rate], face, start) * dt * active_fraction(agents_.age[a], dt, activation_time);

    if (!terminate) {
      const TraceResult r = move_agent(domain_, agents_, a, move_rate * dt, segments_);
      counters_.face_crossings += r.face_crossings;
      counters_.boundary_hits += r.hit_boundary ? 1 : 0;
      deposit_along_path(domain_, segments_, deposit, face, start, deposit_amount_);
      continue;
    }
    // Terminate: the walk stops at the boundary and the agent deposits only for the part of the
    // step it walked (the same deposit per length as a full step), then turnover respawns it.
    const double distance = move_rate * dt;
    const TraceResult r = move_agent(domain_, agents_, a, distance, segments_, BoundaryRule::Stop);
    counters_.face_crossings += r.face_crossings;
    counters_.boundary_hits += r.hit_boundary ? 1 : 0;
    terminated_[static_cast<size_t>(a)] = r.hit_boundary ? 1 : 0;
    const double walked = r.hit_boundary && distance > 0.0 ? r.length / distance : 1.0;
    deposit_along_path(domain_, segments_, deposit * walked, face, start, deposit_amount_);
  }
}

void ReferenceSimulation::step() {
  const double dt = settings_.time_step;
  const auto step_index = static_cast<std::uint32_t>(steps_taken_);

  sense_and_steer(domain_, params_, layers_[0], dt, settings_.seed, step_index, agents_,
                  &counters_.sensor_face_crossings, controls_.read_stimulus.empty() ? nullptr : &controls_.read_stimulus);
  if (controls_.bias) apply_directional_bias(domain_, *controls_.bias, dt, agents_);
  std::fill(deposit_amount_.begin(), deposit_amount_.end(), 0.0);
  move_and_deposit();
  counters_.respawns += advance_turnover(domain_, hazard_rate_, dt, settings_.seed, step_index, agents_, nullptr,
                                         spawn_rule_, terminated_.empty() ? nullptr : &terminated_);

  // One dynamic layer today: the pheromone every agent deposits into. Static layers (after the
  // dynamic ones) never advance.
  static_assert(kDynamicLayers == 1);
  field_model_.advance(layers_[0], deposit_amount_);

  counters_.agent_steps += agents_.count();
  ++steps_taken_;
  // Time as steps * dt rather than a running sum, so long runs do not drift.
  time_ = static_cast<double>(steps_taken_) * dt;
}

const IntrinsicVertexData<double>& ReferenceSimulation::checked_layer(int layer, const char* what) const {
  check_layer_index(layer, layer_count(), "simulation", what);
  return layers_[static_cast<size_t>(layer)];
}

int ReferenceSimulation::add_static_layer(const IntrinsicVertexData<double>& values) {
  const int layer = layer_count();
  check_layer_values(values, domain_.vertex_count, layer, "simulation", "add_static_layer");
  layers_.push_back(values);
  return layer;
}

IntrinsicVertexData<double> ReferenceSimulation::field_values(int layer) const {
  return checked_layer(layer, "field_values");
}

void ReferenceSimulation::set_field(const IntrinsicVertexData<double>& values, int layer) {
  checked_layer(layer, "set_field");
  check_layer_values(values, domain_.vertex_count, layer, "simulation", "set_field");
  layers_[static_cast<size_t>(layer)] = values;
}

void ReferenceSimulation::fill_field(double value, int layer) {
  checked_layer(layer, "fill_field");
  check_layer_value(value, layer, "simulation", "fill_field");
  IntrinsicVertexData<double>& f = layers_[static_cast<size_t>(layer)];
  f.assign(f.size(), value);
}

FieldStatistics ReferenceSimulation::field_statistics(double U, int layer) const {
  return compute_field_statistics(checked_layer(layer, "field_statistics"), domain_.vertex_mass, U);
}

}  // namespace physarum
