#include "reference/agent_simulation.hpp"

#include "common/simulation/simulation_state.hpp"

#include "common/model/agent_model.hpp"
#include "common/model/directional_bias.hpp"
#include "common/model/domain_sampling.hpp"
#include "common/base/errors.hpp"
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

// Every species' parameters, the matrix, and the agents adding up to the settings' count.
const SpeciesSet& checked(const SurfaceDomain& domain, const SpeciesSet& species, const SimulationSettings& settings) {
  check_species(species, domain.vertex_count, "simulation");
  for (const Species& s : species.species) {
    SimulationSettings one = settings;
    one.agents = s.agents;
    check_simulation_inputs(domain, s.parameters, one, "simulation");
  }
  if (species.total_agents() != settings.agents)
    throw InputError("simulation: the species have " + std::to_string(species.total_agents()) + " agents in all, the settings " +
                     std::to_string(settings.agents));
  return species;
}

// The per-vertex controls (read-stimulus; the write rate is the field model's to check).
const SimulationControls& checked(const SurfaceDomain& domain, const SimulationControls& controls) {
  check_controls(domain, controls, "simulation");
  return controls;
}

}  // namespace

ReferenceAgentSimulation::ReferenceAgentSimulation(const SurfaceDomain& domain, VertexParameters params,
                                         const SimulationSettings& settings)
    : ReferenceAgentSimulation(domain, std::move(params), SimulationControls{}, settings) {}

ReferenceAgentSimulation::ReferenceAgentSimulation(const SurfaceDomain& domain, VertexParameters params,
                                         const SimulationControls& controls, const SimulationSettings& settings)
    : ReferenceAgentSimulation(domain, SpeciesSet::single(settings.agents, checked(domain, params, settings)), controls, settings) {}

ReferenceAgentSimulation::ReferenceAgentSimulation(const SurfaceDomain& domain, const SpeciesSet& species,
                                         const SimulationControls& controls, const SimulationSettings& settings)
    : domain_(domain),
      species_set_(checked(domain, species, settings)),
      controls_(checked(domain, controls)),
      settings_(settings),
      layers_(std::vector<IntrinsicVertexData<double>>(static_cast<size_t>(species.count()),
                                                   IntrinsicVertexData<double>(static_cast<size_t>(domain.vertex_count), 0.0)),
              domain.vertex_count, "simulation") {
  for (int s = 0; s < species_set_.count(); ++s) {
    const Species& given = species_set_.species[static_cast<size_t>(s)];
    auto state = std::make_unique<SpeciesState>();
    state->params = given.parameters;
    state->hazard_rate = hazard_rate_per_vertex(state->params[Param::mean_lifetime]);
    state->spawn = build_spawn_distribution(domain_, controls_.spawn_weight, state->hazard_rate);
    state->spawn_rule = SpawnRule{&state->spawn, controls_.spawn_heading, controls_.bias ? &*controls_.bias : nullptr};
    state->field_model = std::make_unique<ReferenceDiffusionDecay>(domain_, state->params, settings.integrator, settings.time_step);
    // The write-stimuli add pheromone independently of the agents: to every species' layer alike.
    state->field_model->set_write_rate(controls_.write_rate);
    state->deposit_amount.assign(static_cast<size_t>(domain.vertex_count), 0.0);
    const int first = species_set_.first_agent(s);
    state->agents = AgentRange{first, first + given.agents};
    agents_.append(initialise_agents(domain_, state->hazard_rate, state->params[Param::turn_frequency],
                                     state->params[Param::turn_rate], given.agents, settings.seed, state->spawn_rule, first));
    species_.push_back(std::move(state));
  }
  if (!species_set_.is_single()) sensed_.assign(static_cast<size_t>(domain.vertex_count), 0.0);
  segments_.reserve(64);
  if (controls_.boundary == BoundaryBehaviour::Terminate) terminated_.assign(static_cast<size_t>(settings.agents), 0);
}

void ReferenceAgentSimulation::move_and_deposit() {
  const double dt = settings_.time_step;
  const bool terminate = controls_.boundary == BoundaryBehaviour::Terminate;
  for (const auto& species : species_) {
    const VertexParameters& params = species->params;
    IntrinsicVertexData<double>& deposit_amount = species->deposit_amount;
    for (int a = species->agents.begin; a < species->agents.end; ++a) {
      // Rates are read where the step starts.
      const int face = agents_.face[a];
      const Eigen::Vector2d start = agents_.position[a];
      const double move_rate = interpolate_vertex_field(domain_, params[Param::move_rate], face, start);
      const double activation_time = interpolate_vertex_field(domain_, params[Param::activation_time], face, start);
      const double deposit =
          interpolate_vertex_field(domain_, params[Param::deposit_rate], face, start) * dt * active_fraction(agents_.age[a], dt, activation_time);

      if (!terminate) {
        const TraceResult r = move_agent(domain_, agents_, a, move_rate * dt, segments_);
        counters_.face_crossings += r.face_crossings;
        counters_.boundary_hits += r.hit_boundary ? 1 : 0;
        deposit_along_path(domain_, segments_, deposit, face, start, deposit_amount);
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
      deposit_along_path(domain_, segments_, deposit * walked, face, start, deposit_amount);
    }
  }
}

const IntrinsicVertexData<double>& ReferenceAgentSimulation::sensed_field(int s) {
  if (species_set_.is_single()) return layers_[0];
  std::fill(sensed_.begin(), sensed_.end(), 0.0);
  for (int j = 0; j < species_count(); ++j) {
    const double m = species_set_.sensing_weight(s, j);
    if (m == 0.0) continue;
    const IntrinsicVertexData<double>& layer = layers_[static_cast<size_t>(j)];
    for (size_t v = 0; v < sensed_.size(); ++v) sensed_[v] += m * layer[v];
  }
  return sensed_;
}

void ReferenceAgentSimulation::step() {
  const double dt = settings_.time_step;
  const auto step_index = static_cast<std::uint32_t>(steps_taken_);
  const IntrinsicVertexData<double>* stimulus = controls_.read_stimulus.empty() ? nullptr : &controls_.read_stimulus;

  for (int s = 0; s < species_count(); ++s) {
    const SpeciesState& species = *species_[static_cast<size_t>(s)];
    sense_and_steer(domain_, species.params, sensed_field(s), dt, settings_.seed, step_index, agents_,
                    &counters_.sensor_face_crossings, stimulus, species.agents);
  }
  if (controls_.bias) apply_directional_bias(domain_, *controls_.bias, dt, agents_);
  for (const auto& species : species_) std::fill(species->deposit_amount.begin(), species->deposit_amount.end(), 0.0);
  move_and_deposit();
  for (const auto& species : species_)
    counters_.respawns += advance_turnover(domain_, species->hazard_rate, dt, settings_.seed, step_index, agents_, nullptr,
                                           species->spawn_rule, terminated_.empty() ? nullptr : &terminated_, species->agents);

  // Each species' layer advances with its own deposits and rates. Static layers (after the dynamic
  // ones) never advance.
  for (int s = 0; s < species_count(); ++s) {
    SpeciesState& species = *species_[static_cast<size_t>(s)];
    species.field_model->advance(layers_[static_cast<size_t>(s)], species.deposit_amount);
  }

  counters_.agent_steps += agents_.count();
  ++steps_taken_;
  // Time as steps * dt rather than a running sum, so long runs do not drift.
  time_ = static_cast<double>(steps_taken_) * dt;
}

SimulationState ReferenceAgentSimulation::save_state() const {
  SimulationState state;
  state.steps_taken = steps_taken_;
  state.time = time_;
  state.layers = layers_.all();
  state.agents = agents_;
  state.counters = counters_;
  return state;
}

// Copied element by element into the buffers sized at construction (step() keeps allocating
// nothing afterwards). The per-step scratch (deposit amounts, sensed sums, trace segments) is
// rewritten before it is read in every step, so it is not part of the state.
void ReferenceAgentSimulation::restore_state(const SimulationState& state) {
  check_state_fits(state, layer_count(), domain_.vertex_count, agents_.count(), domain_.face_count, "simulation");
  layers_.copy_from(state.layers);
  agents_ = state.agents;
  counters_ = state.counters;
  steps_taken_ = state.steps_taken;
  time_ = state.time;
}

FieldStatistics ReferenceAgentSimulation::field_statistics(double U, int layer) const {
  return compute_field_statistics(layers_.checked(layer, "field_statistics"), domain_.vertex_mass, U);
}

}  // namespace physarum
