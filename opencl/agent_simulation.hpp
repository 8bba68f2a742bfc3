#pragma once
// The OpenCL simulation of the extended slime-mold model (mirrors reference/agent_simulation.hpp): the
// same step, in the same order, on any OpenCL device.
//
//   0.   every sort_interval steps, agents are counting-sorted by face (kernels/agent_order.cl), a
//        memory order only: results do not change
//   1-3. agent_step kernel (kernels/agent_step.cl): sense + steer (+ bias), move + deposit, turnover
//
// The controls of Sec. 3.3 (common/model/simulation_controls.hpp) are compiled into the kernels as build
// options only when present (read-stimulus, spawn weights, bias, spawn heading, terminate) and the
// write rate is one extra launch per sub-step of the field model: default controls run the same
// kernels, bit for bit, at the same speed as before controls existed.
//   4.   fields: every dynamic layer advances with this step's deposits, where its model puts
//        them (opencl/field_model.hpp; one diffusion-decay layer per species,
//        opencl/diffusion_decay.hpp); static layers (opencl/static_field.hpp) do not take part
//
// Competing species (common/model/species.hpp, kernels/species.cl) are compiled in only when there are
// several (-DPHYSARUM_SPECIES=K): before the sensing, each species' sensed field sum_j m_sj layer_j
// is built on the device; the kernels take each agent's species from its id. One species runs the
// base model's kernels, bit for bit.
//   5.   time += dt
//
// step() only enqueues: forward Euler runs with no host round trip at all; backward Euler reads the
// 32-byte solver state every few CG iterations. Everything stays on the device until a read is
// asked for (concentration, statistics, agents, counters).
//
// Deposits accumulate as 64-bit fixed point, scale 2^k (deposit_scale(), opencl/deposit_scale.hpp):
// k is the largest that keeps the worst case of one step (every agent's whole deposit into one
// vertex) below 2^62, and the constructor refuses a scene where even that leaves fewer than 2^20
// units for one agent's deposit of one step (rounding would then matter at the 1e-6 level).
#include "common/model/simulation_controls.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/model/species.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/model/vertex_parameters.hpp"
#include "kernels/device_types.h"
#include "opencl/agent_order.hpp"
#include "opencl/agents.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/field.hpp"
#include "opencl/field_model.hpp"
#include "opencl/face_records.hpp"
#include "opencl/diffusion_decay.hpp"
#include "opencl/static_field.hpp"

#include <memory>
#include <string>
#include <vector>

namespace physarum::opencl {

struct OpenCLBackendOptions {
  OpenCLDiffusionDecayOptions pheromone;
  // Agents are re-sorted by face every this many steps (kernels/agent_order.cl), so that agents
  // adjacent in memory read the same face records; 0 never sorts. Sorting changes no result.
  int sort_interval = 8;
  // Agents per move walker, 1..4 (kernels/agent_step.cl); 0 takes the device's tuning
  // (opencl/runtime/device_tuning.hpp: 4 on CPU devices, where agents moving in vector lanes overlap their
  // face reads, and 1 elsewhere). More than 1 also makes the
  // walks vector lanes (kernels/lanes.h), 1 scalars, and gives each agent_step work-item
  // PHYSARUM_VECTOR_MOVE_WALKERS walkers. Changes no result.
  int agents_per_work_item = 0;
  // Extra OpenCL build options for the agent and pheromone programs (the differential harness plants
  // faults with -D flags, opencl/planted_faults.hpp).
  std::string build_options;
};

class OpenCLAgentSimulation final : public SimulationBackend {
 public:
  // Uploads the domain (face records, alias table), the parameters and builds the kernels; places
  // the agents on the device with the reference's initial-state rule. Throws InputError on bad
  // parameters and DeviceError when a buffer exceeds the device or a kernel fails to build.
  OpenCLAgentSimulation(const ComputeContext& compute, const SurfaceDomain& domain, const VertexParameters& params,
                   const SimulationSettings& settings, const OpenCLBackendOptions& options = {});
  // With the controls of Sec. 3.3; the same InputErrors as ReferenceAgentSimulation for bad controls.
  OpenCLAgentSimulation(const ComputeContext& compute, const SurfaceDomain& domain, const VertexParameters& params,
                   const SimulationControls& controls, const SimulationSettings& settings,
                   const OpenCLBackendOptions& options = {});
  // Competing species (common/model/species.hpp; copied); settings.agents must be their total. The same
  // InputErrors as ReferenceAgentSimulation's species constructor, and one more: species whose sinks
  // differ (they would spawn in different places; the kernels keep one spawn table).
  OpenCLAgentSimulation(const ComputeContext& compute, const SurfaceDomain& domain, const SpeciesSet& species,
                   const SimulationControls& controls, const SimulationSettings& settings,
                   const OpenCLBackendOptions& options = {});
  ~OpenCLAgentSimulation() override;
  OpenCLAgentSimulation(const OpenCLAgentSimulation&) = delete;
  OpenCLAgentSimulation& operator=(const OpenCLAgentSimulation&) = delete;

  // Enqueues one step (see the header comment).
  void step() override;
  void finish() override;

  double time() const override { return static_cast<double>(steps_taken_) * settings_.time_step; }
  long long steps_taken() const override { return steps_taken_; }
  // Fields in the domain's vertex order (the device keeps its own locality order). One dynamic
  // layer per species (the pheromone, for one species); static layers after them.
  int layer_count() const override { return static_cast<int>(layers_.size() + static_fields_.size()); }
  int dynamic_layer_count() const override { return static_cast<int>(layers_.size()); }
  int add_static_layer(const IntrinsicVertexData<double>& domain_values) override;
  IntrinsicVertexData<double> field_values(int layer = 0) const override;
  void set_field(const IntrinsicVertexData<double>& domain_values, int layer = 0) override;
  void fill_field(double value, int layer = 0) override;
  FieldStatistics field_statistics(double U, int layer = 0) const override;
  std::vector<int> agent_faces() const override;
  SimulationCounters counters() const override;
  // Reads back / uploads every layer, the agents (in id order, domain faces) and the counters; the
  // agents come back in id order, so after a restore their memory order differs from the saved
  // run's until the next sort, which changes no result (agent_order.hpp).
  SimulationState save_state() const override;
  void restore_state(const SimulationState& state) override;
  std::string backend_name() const override { return "opencl"; }
  std::string device_name() const override;

  // ---- for tests: identical states in, identical states out ----
  Agents read_agents() const;
  void write_agents(const Agents& agents);
  // A device layer itself (dynamic or static), in the device's vertex order (face_records.hpp):
  // for order-free uses (fill, total_amount); per-vertex values go through field_values / set_field.
  // Throws InputError for an index out of range.
  OpenCLField& layer(int index) const;
  double deposit_scale() const { return deposit_scale_; }
  bool fixed_point_deposits() const { return fixed_point_; }
  // Names of device buffers a kernel wrote past (empty when every canary is intact), static layers'
  // included.
  std::vector<std::string> damaged_canaries() const;

 private:
  struct Kernels;
  // What the constructor's steps hand on to each other (defined in the .cpp; gone once built).
  struct Setup;
  // The constructor's steps, in the constructor's order (each needs the ones before it).
  // Checks species, controls and options as the reference does; the spawn table and device tuning.
  Setup check_inputs(const SpeciesSet& species, const SimulationControls& controls,
                     const OpenCLBackendOptions& options);
  // face_order_, vertex_order_, and the domain and parameters renumbered and packed in them.
  void order_for_device(Setup& setup);
  // fixed_point_ and deposit_scale_, and the deposit cells' layout (per species when competing).
  void choose_deposits(Setup& setup);
  void set_step_constants(const Setup& setup);
  // The agent program's build options: the controls present and the species, as -D flags.
  std::string agent_build_options(const Setup& setup) const;
  // Builds both programs and takes their kernels; returns the agent program (agent_order_ uses it too).
  cl::Program build_kernels(const Setup& setup);
  // agent_groups_, step_groups_, sensing_groups_ from the built kernels' work-group sizes.
  void count_work_groups(int agent_count);
  // Face records, the device's face map, the vertex parameters and the domain's face sampler.
  void upload_domain_buffers(const Setup& setup);
  // The controls' arrays, in device order (placeholders where absent).
  void upload_control_buffers(const Setup& setup);
  // deposits_, and with competing species their sub-buffers, sensed_ and sensing_matrix_.
  void allocate_deposits(const Setup& setup);
  // The agents, their step's scratch and counters, and the sort (agent_order_).
  void allocate_agent_buffers(int agent_count, const cl::Program& agent_program);
  // One dynamic layer (diffusion-decay) per species.
  void make_layers(const Setup& setup);
  // Clears the accumulators and places the agents with the reference's initial-state rule; waits.
  void place_agents();
  void enqueue_agent_step();
  void enqueue_sensing();
  void enqueue_species_sensed_fields();
  // What the sensing kernels read: layer 0 for one species, sensed_ for competing species.
  const cl::Buffer& sensed_buffer() const;
  OpenCLField& checked_layer(int index, const char* what) const;

  ComputeContext compute_;
  const SurfaceDomain& domain_;
  SimulationSettings settings_;
  int sort_interval_ = 0;
  FaceOrder face_order_;
  VertexOrder vertex_order_;
  std::unique_ptr<Kernels> kernels_;
  PhysarumStepConstants constants_{};
  std::vector<std::unique_ptr<OpenCLFieldLayer>> layers_;  // dynamic layers, one per species
  std::vector<std::unique_ptr<OpenCLStaticField>> static_fields_;  // layers layers_.size() and on
  DeviceBuffer faces_, vertex_parameters_, alias_probability_, alias_index_, device_face_;
  // The controls' arrays (device orders), one-element placeholders for those absent (never read then).
  DeviceBuffer read_stimulus_, spawn_alias_probability_, spawn_alias_index_, spawn_weight_;
  DeviceBuffer bias_direction_, bias_strength_;
  DeviceBuffer deposits_, group_counters_;
  // Competing species only (kernels/species.cl; empty for one species): each species' deposit cells
  // (sub-buffers of deposits_), the sensed field of each species (sum_j m_sj layer_j, species by
  // species) and the K x K matrix.
  std::vector<DeviceBuffer> species_deposits_;
  DeviceBuffer sensed_, sensing_matrix_;
  DeviceBuffer deciders_, decider_count_, first_sensing_;  // agents sensed ahead of the step (sense_deciders)
  DeviceAgents agents_;
  std::unique_ptr<DeviceAgentOrder> agent_order_;  // sorts agents_ by face (absent when sort_interval is 0)
  // agent_groups_ work-groups cover one agent per work-item (initialise, sort); step_groups_ cover
  // agents_per_work_item_ per walker (agent_step); sensing_groups_ run sense_deciders, which loops
  // over the step's deciders.
  std::size_t agent_group_ = 1, agent_groups_ = 1, step_groups_ = 1;
  std::size_t sensing_group_ = 1, sensing_groups_ = 1;
  int agents_per_work_item_ = 1;
  bool fixed_point_ = true;
  double deposit_scale_ = 1.0;
  long long steps_taken_ = 0;
};

}  // namespace physarum::opencl
