#pragma once
// The serial reference simulation of the extended slime-mold model (paper Sec. 3.2-3.3): the oracle
// every faster backend is judged against. One step, in this order:
//
//   1. sense + steer   (sensing_steering.hpp) every agent whose turn decision is due; sensors read
//                      the pheromone plus the read-stimulus (controls)
//   1b. bias           (directional_bias.hpp) when the controls have one
//   2. move + deposit  (movement.hpp, deposition.hpp) along the path, into an amount buffer
//   3. turnover        (turnover.hpp) age, exposure, respawn (also of agents in a sink face or, with
//                      BoundaryBehaviour::Terminate, that reached a boundary)
//   4. fields          the field model (field_model.hpp; today diffusion_decay.hpp, Eq. 6 / 7)
//                      advances every dynamic layer with this step's deposits, in its own order
//   5. time += dt
//
// The simulation holds a list of per-vertex field layers: the dynamic ones first (one pheromone
// layer per species, common/model/species.hpp: species i deposits only into layer i and its sensors read
// sum_j m_ij * layer_j, each layer decaying and diffusing with its species' rates), then static ones
// (fixed maps). Agents are numbered species by species, so every species works on a contiguous run
// of ids and the random streams stay keyed by id; one species reading its layer with weight 1 is
// the base model bit for bit (the sensors then read layer 0 itself).
//
// The controls of Sec. 3.3 (common/model/simulation_controls.hpp) arrive evaluated; default controls are
// the base model bit for bit (every control's work is skipped when it is absent).
//
// All randomness comes from Philox streams keyed (seed, agent), counter (step, purpose)
// (common/base/random_streams.hpp), so a run is bit-reproducible. step() allocates nothing and
// recomputes no geometry: every buffer is sized once here (counted in
// tests/test_reference_allocations.cpp; with a spatially varying diffuse rate the backward-Euler
// solve goes through Eigen's SparseLU, whose solve() allocates).
#include "common/model/simulation_controls.hpp"
#include "common/model/spawn_distribution.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/surface/trace.hpp"
#include "common/model/species.hpp"
#include "common/model/vertex_parameters.hpp"
#include "common/model/agents.hpp"
#include "common/base/element_data.hpp"
#include "reference/diffusion_decay.hpp"
#include "reference/field_layers.hpp"
#include "reference/turnover.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace physarum {

class ReferenceAgentSimulation final : public SimulationBackend {
 public:
  // The domain must outlive the simulation (it is read, never copied). Throws InputError when the
  // parameter arrays do not match the domain or a setting is out of range.
  ReferenceAgentSimulation(const SurfaceDomain& domain, VertexParameters params, const SimulationSettings& settings);
  // With the controls of Sec. 3.3 (copied). Throws InputError when a control does not match the
  // domain (sizes, non-finite values, negative spawn weights, all spawn weights zero, symmetry).
  ReferenceAgentSimulation(const SurfaceDomain& domain, VertexParameters params, const SimulationControls& controls,
                      const SimulationSettings& settings);
  // Competing species (copied); settings.agents must be their total. Throws InputError when the set
  // does not match the domain (common/model/species.hpp: check_species) or the count differs.
  ReferenceAgentSimulation(const SurfaceDomain& domain, const SpeciesSet& species, const SimulationControls& controls,
                      const SimulationSettings& settings);
  // Not copyable: the spawn rule points into this object's own controls.
  ReferenceAgentSimulation(const ReferenceAgentSimulation&) = delete;
  ReferenceAgentSimulation& operator=(const ReferenceAgentSimulation&) = delete;

  void step() override;

  double time() const override { return time_; }
  long long steps_taken() const override { return steps_taken_; }
  double time_step() const { return settings_.time_step; }
  std::uint32_t seed() const { return settings_.seed; }

  const SurfaceDomain& domain() const { return domain_; }
  // Species 0's parameters (every agent's in a one-species simulation).
  const VertexParameters& parameters() const { return species_.front()->params; }
  int species_count() const { return static_cast<int>(species_.size()); }
  const SpeciesSet& species() const { return species_set_; }
  const SimulationControls& controls() const { return controls_; }
  const SpawnDistribution& spawn_distribution() const { return species_.front()->spawn; }
  const Agents& agents() const { return agents_; }
  Agents& agents() { return agents_; }  // tests place agents by hand
  // A layer itself (any layer; std::out_of_range past the end). The reference may be invalidated
  // by add_static_layer.
  const IntrinsicVertexData<double>& field(int layer = 0) const { return layers_.at(layer); }
  IntrinsicVertexData<double>& field(int layer = 0) { return layers_.at(layer); }
  // Species 0's field model (the pheromone's, in a one-species simulation).
  ReferenceDiffusionDecay& field_model() { return *species_.front()->field_model; }
  const ReferenceDiffusionDecay& field_model() const { return *species_.front()->field_model; }
  SimulationCounters counters() const override { return counters_; }

  // ---- SimulationBackend ----
  int layer_count() const override { return layers_.size(); }
  int dynamic_layer_count() const override { return species_count(); }
  int add_static_layer(const IntrinsicVertexData<double>& values) override { return layers_.add_static(values); }
  IntrinsicVertexData<double> field_values(int layer = 0) const override { return layers_.checked(layer, "field_values"); }
  void set_field(const IntrinsicVertexData<double>& values, int layer = 0) override { layers_.set(values, layer); }
  void fill_field(double value, int layer = 0) override { layers_.fill(value, layer); }
  FieldStatistics field_statistics(double U, int layer = 0) const override;
  std::vector<int> agent_faces() const override { return agents_.face; }
  SimulationState save_state() const override;
  void restore_state(const SimulationState& state) override;
  std::string backend_name() const override { return "reference"; }
  std::string device_name() const override { return "CPU (serial reference, 1 thread)"; }
  // Species 0's hazard rate 1/tau per vertex (common/model/agent_model.hpp).
  const IntrinsicVertexData<double>& hazard_rate() const { return species_.front()->hazard_rate; }

 private:
  void move_and_deposit();

  // What sensors of species s read: layer s itself for the base model, else sensed_ filled with
  // sum_j m_sj * layer_j.
  const IntrinsicVertexData<double>& sensed_field(int s);

  // Everything one species owns. Held by pointer: spawn_rule points into spawn.
  struct SpeciesState {
    VertexParameters params;
    IntrinsicVertexData<double> hazard_rate;
    SpawnDistribution spawn;
    SpawnRule spawn_rule;  // points into spawn and controls_
    std::unique_ptr<ReferenceDiffusionDecay> field_model;
    IntrinsicVertexData<double> deposit_amount;  // amount per vertex deposited during the current step
    AgentRange agents;
  };

  const SurfaceDomain& domain_;
  SpeciesSet species_set_;
  SimulationControls controls_;
  SimulationSettings settings_;
  std::vector<std::unique_ptr<SpeciesState>> species_;
  Agents agents_;
  // The dynamic layers (one per species), then the static ones in the order they were added.
  FieldLayers layers_;

  double time_ = 0.0;
  long long steps_taken_ = 0;
  SimulationCounters counters_;

  // Per-step scratch, sized once.
  IntrinsicVertexData<double> sensed_;  // sensed_field's sum (empty for one species reading its own layer)
  std::vector<TraceSegment> segments_;
  std::vector<unsigned char> terminated_;  // agents whose move met a boundary (Terminate only)
};

}  // namespace physarum
