#include "opencl/agent_simulation.hpp"

#include "common/simulation/simulation_state.hpp"

#include "common/base/errors.hpp"
#include "opencl/agent_order.hpp"
#include "opencl/agent_parameters.hpp"
#include "opencl/deposit_scale.hpp"
#include "opencl/runtime/device_tuning.hpp"
#include "opencl/face_records.hpp"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/kernel_sources.hpp"
#include "opencl/runtime/opencl_error.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "opencl/runtime/work_group_size.hpp"
#include "common/base/random_streams.hpp"
#include "common/surface/trace.hpp"
#include "common/model/agent_model.hpp"
#include "common/model/spawn_distribution.hpp"

#include <algorithm>
#include <cmath>

namespace physarum::opencl {

struct OpenCLAgentSimulation::Kernels {
  cl::Kernel initialise, collect_deciders, sense_deciders, agent_step;
  cl::Kernel add_layer_to_sensed;  // competing species only (kernels/species.cl)
};

namespace {

static_assert(sizeof(PhysarumStepConstants) == 8 * 4 + sizeof(PhysarumAgentParameters),
              "PhysarumStepConstants: eight 4-byte fields and the uniform parameter record");
// The bounds the kernels share with the reference must be the reference's.
static_assert(PHYSARUM_MAX_TRACE_STEPS == kMaxTraceSteps);
static_assert(PHYSARUM_MAX_TURN_DECISIONS_PER_STEP == kMaxTurnDecisionsPerStep);
static_assert(PHYSARUM_PURPOSE_INITIAL_PLACEMENT == static_cast<unsigned>(RandomPurpose::InitialPlacement) &&
              PHYSARUM_PURPOSE_INITIAL_STATE == static_cast<unsigned>(RandomPurpose::InitialState) &&
              PHYSARUM_PURPOSE_TURN_DIRECTION == static_cast<unsigned>(RandomPurpose::TurnDirection) &&
              PHYSARUM_PURPOSE_RESPAWN_PLACEMENT == static_cast<unsigned>(RandomPurpose::RespawnPlacement) &&
              PHYSARUM_PURPOSE_RESPAWN_STATE == static_cast<unsigned>(RandomPurpose::RespawnState) &&
              PHYSARUM_PURPOSE_INITIAL_SPAWN_CORNER == static_cast<unsigned>(RandomPurpose::InitialSpawnCorner) &&
              PHYSARUM_PURPOSE_RESPAWN_CORNER == static_cast<unsigned>(RandomPurpose::RespawnCorner));
static_assert(static_cast<float>(kTurnDecisionTolerance) == PHYSARUM_TURN_DECISION_TOLERANCE);

// The species, checked as the reference checks them (reference/agent_simulation.cpp): each species'
// parameters like a one-species simulation's, then the set itself, and the agents adding up.
void check_species_inputs(const SurfaceDomain& domain, const SpeciesSet& species, const SimulationSettings& settings) {
  for (const Species& s : species.species) {
    SimulationSettings one = settings;
    one.agents = species.count() == 1 ? settings.agents : s.agents;
    check_simulation_inputs(domain, s.parameters, one, "opencl simulation");
  }
  check_species(species, domain.vertex_count, "opencl simulation");
  if (species.total_agents() != settings.agents)
    throw InputError("opencl simulation: the species have " + std::to_string(species.total_agents()) +
                     " agents in all, the settings " + std::to_string(settings.agents));
}

bool same_spawn(const SpawnDistribution& a, const SpawnDistribution& b) {
  return a.weighted == b.weighted && a.vertex_weight == b.vertex_weight &&
         a.face_sampler.probability == b.face_sampler.probability && a.face_sampler.alias == b.face_sampler.alias;
}

// The largest deposit rate of any species at each vertex: the fixed-point scale must hold the worst
// step of whichever species deposits most.
IntrinsicVertexData<double> largest_deposit_rate(const SpeciesSet& species) {
  IntrinsicVertexData<double> largest = species.species.front().parameters[Param::deposit_rate];
  for (const Species& s : species.species)
    for (size_t v = 0; v < largest.size(); ++v) largest[v] = std::max(largest[v], s.parameters[Param::deposit_rate][v]);
  return largest;
}

// Deposit cells per species, rounded up so that each species' cells start where the device allows a
// sub-buffer to start (CL_DEVICE_MEM_BASE_ADDR_ALIGN, in bits).
size_t species_cell_stride(const DeviceInfo& device, size_t vertex_count, size_t cell_bytes) {
  const size_t align_bytes = std::max<size_t>(device.device.getInfo<CL_DEVICE_MEM_BASE_ADDR_ALIGN>() / 8, cell_bytes);
  const size_t bytes = (vertex_count * cell_bytes + align_bytes - 1) / align_bytes * align_bytes;
  return std::max<size_t>(bytes / cell_bytes, 1);
}

constexpr cl_mem_flags kRead = CL_MEM_READ_ONLY;

}  // namespace

// What the constructor's steps hand on to each other: the inputs, their device order, and the choices
// made from them. Needed only while building; the members keep what the kernels read.
struct OpenCLAgentSimulation::Setup {
  Setup(const SpeciesSet& species_in, const SimulationControls& controls_in, const OpenCLBackendOptions& options_in)
      : species(species_in), controls(controls_in), options(options_in) {}

  const SpeciesSet& species;
  const SimulationControls& controls;
  const OpenCLBackendOptions& options;
  bool competing = false;
  int species_count = 0;
  int agent_count = 0;
  size_t nv = 0;
  SpawnDistribution spawn;
  DeviceTuning tuning;
  // The domain with vertices in device order: what the face records and the field are built from
  // (needed only here; the buffers keep what the kernels read).
  SurfaceDomain device_domain;
  std::vector<VertexParameters> device_params;
  PackedAgentParameters agent_parameters;
  size_t cell_bytes = 0, cell_stride = 0;  // one deposit cell's bytes; cells per species
};

OpenCLAgentSimulation::~OpenCLAgentSimulation() = default;

OpenCLAgentSimulation::OpenCLAgentSimulation(const ComputeContext& compute, const SurfaceDomain& domain,
                                   const VertexParameters& params, const SimulationSettings& settings,
                                   const OpenCLBackendOptions& options)
    : OpenCLAgentSimulation(compute, domain, params, SimulationControls{}, settings, options) {}

OpenCLAgentSimulation::OpenCLAgentSimulation(const ComputeContext& compute, const SurfaceDomain& domain,
                                   const VertexParameters& params, const SimulationControls& controls,
                                   const SimulationSettings& settings, const OpenCLBackendOptions& options)
    : OpenCLAgentSimulation(compute, domain, SpeciesSet::single(settings.agents, params), controls, settings, options) {}

OpenCLAgentSimulation::OpenCLAgentSimulation(const ComputeContext& compute, const SurfaceDomain& domain, const SpeciesSet& species,
                                   const SimulationControls& controls, const SimulationSettings& settings,
                                   const OpenCLBackendOptions& options)
    : compute_(compute), domain_(domain), settings_(settings), sort_interval_(options.sort_interval) {
  // In this order: each step needs the ones before it, and the device sees its calls and
  // allocations in the order it always has (the same buffers, the same bits).
  Setup setup = check_inputs(species, controls, options);
  order_for_device(setup);
  choose_deposits(setup);
  set_step_constants(setup);
  const cl::Program agent_program = build_kernels(setup);
  count_work_groups(setup.agent_count);
  upload_domain_buffers(setup);
  upload_control_buffers(setup);
  allocate_deposits(setup);
  allocate_agent_buffers(setup.agent_count, agent_program);
  make_layers(setup);
  place_agents();
}

OpenCLAgentSimulation::Setup OpenCLAgentSimulation::check_inputs(const SpeciesSet& species,
                                                                 const SimulationControls& controls,
                                                                 const OpenCLBackendOptions& options) {
  check_species_inputs(domain_, species, settings_);
  check_controls(domain_, controls, "opencl simulation");
  Setup setup(species, controls, options);
  // One species reading its own layer with weight 1 runs the base model's kernels, bit for bit.
  setup.competing = !species.is_single();
  setup.species_count = species.count();
  const VertexParameters& params = species.species.front().parameters;
  setup.spawn =
      build_spawn_distribution(domain_, controls.spawn_weight, hazard_rate_per_vertex(params[Param::mean_lifetime]));
  // The kernels keep one spawn table for every agent: species whose sinks differ (and so spawn
  // elsewhere) are refused rather than spawned where another species would be.
  for (int s = 1; s < setup.species_count; ++s) {
    const VertexParameters& own = species.species[static_cast<size_t>(s)].parameters;
    if (!same_spawn(setup.spawn, build_spawn_distribution(domain_, controls.spawn_weight,
                                                          hazard_rate_per_vertex(own[Param::mean_lifetime]))))
      throw InputError("opencl simulation: species " + std::to_string(s) +
                       " has its sinks (mean_lifetime 0) elsewhere than species 0, so it would spawn elsewhere; the "
                       "OpenCL backend spawns every species alike (use --backend reference)");
  }
  if (options.agents_per_work_item < 0 || options.agents_per_work_item > 4)
    throw InputError("opencl simulation: agents_per_work_item must be 0 (automatic) or 1..4, got " +
                     std::to_string(options.agents_per_work_item));
  setup.tuning = tuning_for(compute_.device);
  agents_per_work_item_ =
      options.agents_per_work_item > 0 ? options.agents_per_work_item : setup.tuning.agents_per_work_item;
  setup.nv = static_cast<size_t>(domain_.vertex_count);
  setup.agent_count = settings_.agents;
  return setup;
}

void OpenCLAgentSimulation::order_for_device(Setup& setup) {
  // ---- the device's locality order of faces and vertices (face_records.hpp) ----
  face_order_ = locality_face_order(domain_);
  vertex_order_ = locality_vertex_order(domain_, face_order_);
  setup.device_domain = renumber_vertices(domain_, vertex_order_);
  for (const Species& s : setup.species.species)
    setup.device_params.push_back(renumber_parameters(s.parameters, vertex_order_));

  // ---- parameters per vertex, and whether they are all one value ----
  // Competing species: every species' records one after the other (kernels/species.cl), read per vertex.
  PackedAgentParameters& agent_parameters = setup.agent_parameters;
  agent_parameters = pack_agent_parameters(setup.device_params.front());
  for (int s = 1; s < setup.species_count; ++s) {
    const PackedAgentParameters own = pack_agent_parameters(setup.device_params[static_cast<size_t>(s)]);
    agent_parameters.per_vertex.insert(agent_parameters.per_vertex.end(), own.per_vertex.begin(), own.per_vertex.end());
  }
  if (setup.competing) {
    agent_parameters.uniform = false;
    agent_parameters.mapped_build_options = every_parameter_mapped_build_options();
  }
}

void OpenCLAgentSimulation::choose_deposits(Setup& setup) {
  // ---- deposit accumulation: fixed point where 64-bit atomics exist ----
  const VertexParameters& params = setup.species.species.front().parameters;
  fixed_point_ = opencl::fixed_point_deposits(compute_.device);
  if (fixed_point_)
    deposit_scale_ =
        fixed_point_deposit_scale(setup.competing ? largest_deposit_rate(setup.species) : params[Param::deposit_rate],
                                  setup.agent_count, settings_.time_step);
  setup.cell_bytes = fixed_point_ ? sizeof(cl_long) : sizeof(cl_float);
  setup.cell_stride = setup.competing ? species_cell_stride(compute_.device, setup.nv, setup.cell_bytes) : setup.nv;
}

void OpenCLAgentSimulation::set_step_constants(const Setup& setup) {
  constants_.dt = static_cast<float>(settings_.time_step);
  constants_.deposit_scale = static_cast<float>(deposit_scale_);
  constants_.seed = settings_.seed;
  constants_.step = 0;
  constants_.agent_count = setup.agent_count;
  constants_.face_count = domain_.face_count;
  constants_.uniform_parameters = setup.agent_parameters.uniform ? 1 : 0;
  constants_.pad = 0;
  constants_.uniform = setup.nv > 0 ? setup.agent_parameters.per_vertex[0] : PhysarumAgentParameters{};
}

std::string OpenCLAgentSimulation::agent_build_options(const Setup& setup) const {
  const SimulationControls& controls = setup.controls;
  std::string build = setup.options.build_options + setup.agent_parameters.mapped_build_options;
  if (!fixed_point_) build += " -DPHYSARUM_FLOAT_DEPOSITS";
  // The controls present, as build options (kernels/agent_step.cl): absent ones compile to nothing.
  if (!controls.read_stimulus.empty()) build += " -DPHYSARUM_READ_STIMULUS";
  if (setup.spawn.weighted) build += " -DPHYSARUM_SPAWN_WEIGHTS";
  if (controls.bias) {
    build += " -DPHYSARUM_BIAS -DPHYSARUM_BIAS_SYMMETRY=" + std::to_string(controls.bias->symmetry);
    if (is_uniform(controls.bias->strength)) build += " -DPHYSARUM_BIAS_UNIFORM_STRENGTH";
    if (controls.spawn_heading == SpawnHeading::Bias) build += " -DPHYSARUM_SPAWN_HEADING_BIAS";
  }
  if (controls.boundary == BoundaryBehaviour::Terminate) build += " -DPHYSARUM_BOUNDARY_TERMINATE";
  if (setup.competing) {
    const int species_count = setup.species_count;
    std::string first_ids;
    for (int s = 0; s <= species_count; ++s) {
      // Two appends, not "," + id: GCC 12 at -O3 takes the latter for an overlapping copy (-Wrestrict).
      if (s) first_ids += ",";
      first_ids += std::to_string(s < species_count ? setup.species.first_agent(s) : setup.agent_count);
    }
    build += " -DPHYSARUM_SPECIES=" + std::to_string(species_count) + " -DPHYSARUM_SPECIES_FIRST_IDS=" + first_ids +
             " -DPHYSARUM_SPECIES_VERTICES=" + std::to_string(setup.nv) +
             " -DPHYSARUM_SPECIES_CELLS=" + std::to_string(setup.cell_stride);
  }
  return build;
}

cl::Program OpenCLAgentSimulation::build_kernels(const Setup& setup) {
  kernels_ = std::make_unique<Kernels>();
  cl::Program agent_program;
  std::string build = agent_build_options(setup);
  // Sensing walks 16 traces at once where agents share vector lanes (CPUs), one where they do not.
  const bool vector_lanes = agents_per_work_item_ > 1;
  const std::string prefetch = setup.tuning.clang_prefetch ? " -DPHYSARUM_CLANG_PREFETCH" : "";
  const std::string sensing_build = build + " -DPHYSARUM_WALK_LANES=" + (vector_lanes ? "16" : "1") + prefetch;
  // Moves too: walkers of 4 lanes taking turns (movement.cl), PHYSARUM_VECTOR_MOVE_WALKERS of them.
  build += " -DPHYSARUM_AGENTS_PER_WORK_ITEM=" + std::to_string(agents_per_work_item_) +
           " -DPHYSARUM_WALK_LANES=" + (vector_lanes ? "4" : "1") + prefetch;
  try {
    const cl::Program program =
        build_program(compute_.context, compute_.device, "agent_step.cl", kernel_source("agent_step.cl"), build);
    kernels_->initialise = cl::Kernel(program, "initialise_agents");
    kernels_->agent_step = cl::Kernel(program, "agent_step");
    if (setup.competing) kernels_->add_layer_to_sensed = cl::Kernel(program, "add_layer_to_sensed");
    agent_group_ = work_group_size(kernels_->agent_step, compute_.device, 64);
    agent_program = program;
  } catch (const cl::Error& e) {
    throw device_error("preparing the agent kernels (agent_step.cl) on " + compute_.device.device_name, e.err());
  }
  try {
    const cl::Program program = build_program(compute_.context, compute_.device, "sensing_steering.cl",
                                              kernel_source("sensing_steering.cl"), sensing_build);
    kernels_->collect_deciders = cl::Kernel(program, "collect_deciders");
    kernels_->sense_deciders = cl::Kernel(program, "sense_deciders");
    sensing_group_ = work_group_size(kernels_->sense_deciders, compute_.device, 64);
  } catch (const cl::Error& e) {
    throw device_error("preparing the sensing kernels (sensing_steering.cl) on " + compute_.device.device_name, e.err());
  }
  return agent_program;
}

void OpenCLAgentSimulation::count_work_groups(int agent_count) {
  // The agents one work-item takes, as the kernels were built for them (build_kernels): 16 traces
  // sensed at once and PHYSARUM_VECTOR_MOVE_WALKERS walkers where agents share vector lanes.
  const bool vector_lanes = agents_per_work_item_ > 1;
  const size_t sensing_agents_per_item = vector_lanes ? PHYSARUM_SENSING_AGENTS_PER_WALKER * PHYSARUM_SENSING_WALKERS : 1;
  const int move_walkers = vector_lanes ? PHYSARUM_VECTOR_MOVE_WALKERS : 1;
  agent_groups_ = padded_global_size(static_cast<size_t>(std::max(agent_count, 1)), agent_group_) / agent_group_;
  const size_t step_agents_per_item = static_cast<size_t>(agents_per_work_item_ * move_walkers);
  const size_t step_items = (static_cast<size_t>(std::max(agent_count, 1)) + step_agents_per_item - 1) /
                            step_agents_per_item;
  step_groups_ = padded_global_size(step_items, agent_group_) / agent_group_;
  const size_t sensing_items = (static_cast<size_t>(std::max(agent_count, 1)) + sensing_agents_per_item - 1) /
                               sensing_agents_per_item;
  // sense_deciders loops over its blocks of agents: 16 work-groups per compute unit keep every unit
  // busy whatever the share of agents that sense.
  sensing_groups_ = std::min<size_t>(padded_global_size(sensing_items, sensing_group_) / sensing_group_,
                                     16 * std::max(1u, compute_.device.compute_units));
}

void OpenCLAgentSimulation::upload_domain_buffers(const Setup& setup) {
  faces_ = upload_random_access_buffer(compute_, "face records", build_face_records(setup.device_domain, face_order_));
  device_face_ = upload_buffer(compute_, "device face of each domain face", face_order_.device_of_domain, kRead, false);
  vertex_parameters_ = upload_buffer(compute_, "vertex parameters", setup.agent_parameters.per_vertex, kRead, false);
  const std::vector<float> probability(domain_.face_sampler.probability.begin(),
                                       domain_.face_sampler.probability.end());
  alias_probability_ = upload_buffer(compute_, "face sampler probabilities", probability, kRead, false);
  alias_index_ = upload_buffer(compute_, "face sampler aliases", domain_.face_sampler.alias, kRead, false);
}

void OpenCLAgentSimulation::upload_control_buffers(const Setup& setup) {
  const SimulationControls& controls = setup.controls;
  const SpawnDistribution& spawn = setup.spawn;
  // ---- the controls' arrays (placeholders of one element where absent) ----
  const auto per_vertex = [&](const char* name, const IntrinsicVertexData<double>& values) {
    if (values.empty()) return upload_buffer(compute_, name, std::vector<float>{0.0f}, kRead, false);
    const DeviceVertexData<double> device_values = to_device_order(values, vertex_order_);
    return upload_buffer(compute_, name, std::vector<float>(device_values.begin(), device_values.end()), kRead, false);
  };
  read_stimulus_ = per_vertex("read stimulus", controls.read_stimulus);
  spawn_weight_ = per_vertex("spawn weights", spawn.weighted ? spawn.vertex_weight : IntrinsicVertexData<double>{});
  if (spawn.weighted) {
    // In domain face order, like the domain's table (device_face maps the answer).
    spawn_alias_probability_ = upload_buffer(
        compute_, "spawn sampler probabilities",
        std::vector<float>(spawn.face_sampler.probability.begin(), spawn.face_sampler.probability.end()), kRead, false);
    spawn_alias_index_ = upload_buffer(compute_, "spawn sampler aliases", spawn.face_sampler.alias, kRead, false);
  } else {
    spawn_alias_probability_ = upload_buffer(compute_, "spawn sampler probabilities", std::vector<float>{0.0f}, kRead, false);
    spawn_alias_index_ = upload_buffer(compute_, "spawn sampler aliases", std::vector<cl_int>{0}, kRead, false);
  }
  // A uniform strength (the usual number in a scene) travels as its one value: no vertex reads.
  const bool uniform_strength = controls.bias && is_uniform(controls.bias->strength);
  bias_strength_ = uniform_strength ? upload_buffer(compute_, "bias strength",
                                                    std::vector<float>{static_cast<float>(controls.bias->strength.front())},
                                                    kRead, false)
                                    : per_vertex("bias strength", controls.bias ? controls.bias->strength
                                                                                : IntrinsicVertexData<double>{});
  std::vector<cl_float2> directions(controls.bias ? static_cast<size_t>(domain_.face_count) : 1, cl_float2{{0.0f, 0.0f}});
  if (controls.bias)
    for (int f = 0; f < domain_.face_count; ++f) {
      const std::array<double, 2>& d = controls.bias->direction[f];
      directions[static_cast<size_t>(face_order_.device_of_domain[static_cast<size_t>(f)])] =
          cl_float2{{static_cast<float>(d[0]), static_cast<float>(d[1])}};
    }
  bias_direction_ = upload_buffer(compute_, "bias directions", directions, kRead, false);
}

void OpenCLAgentSimulation::allocate_deposits(const Setup& setup) {
  const size_t nv = setup.nv, cell_stride = setup.cell_stride, cell_bytes = setup.cell_bytes;
  const int species_count = setup.species_count;
  const size_t cells = setup.competing ? cell_stride * static_cast<size_t>(species_count) : nv;
  deposits_ = fixed_point_ ? allocate_written<cl_long>(compute_, "deposit accumulator", cells)
                          : allocate_written<cl_float>(compute_, "deposit accumulator", cells);
  if (setup.competing) {
    // Each species' cells as a buffer of their own, what its layer's advance empties.
    for (int s = 0; s < species_count; ++s) {
      const cl_buffer_region region{static_cast<size_t>(s) * cell_stride * cell_bytes, nv * cell_bytes};
      DeviceBuffer own;
      own.buffer = deposits_.buffer.createSubBuffer(CL_MEM_READ_WRITE, CL_BUFFER_CREATE_TYPE_REGION, &region);
      own.name = "deposit accumulator of species " + std::to_string(s);
      own.payload_bytes = nv * cell_bytes;
      species_deposits_.push_back(std::move(own));
    }
    sensed_ = allocate_written<cl_float>(compute_, "sensed field of each species", nv * static_cast<size_t>(species_count));
    sensing_matrix_ = upload_buffer(compute_, "sensing matrix",
                                    std::vector<float>(setup.species.sensing.begin(), setup.species.sensing.end()),
                                    kRead, false);
  }
}

void OpenCLAgentSimulation::allocate_agent_buffers(int agent_count, const cl::Program& agent_program) {
  group_counters_ = allocate_written<cl_ulong>(compute_, "agent step counters", agent_groups_ * PHYSARUM_COUNTERS);
  agents_ = DeviceAgents::allocate(compute_, agent_count);
  const size_t agent_slots = static_cast<size_t>(std::max(agent_count, 1));
  deciders_ = allocate_written<cl_int>(compute_, "agents with a decision due", agent_slots);
  decider_count_ = allocate_written<cl_uint>(compute_, "count of agents with a decision due", 1);
  first_sensing_ = allocate_written<cl_uint>(compute_, "first sensing of each agent", agent_slots);
  if (sort_interval_ > 0)
    agent_order_ = std::make_unique<DeviceAgentOrder>(compute_, agent_program, domain_.face_count, agent_count,
                                                      agent_group_, agent_groups_);
}

void OpenCLAgentSimulation::make_layers(const Setup& setup) {
  OpenCLDiffusionDecayOptions pheromone_options = setup.options.pheromone;
  pheromone_options.build_options += " " + setup.options.build_options;
  // One dynamic layer per species, with its species' decay and diffusion: the pheromone its agents
  // deposit into (and, for one species, sense); the write-stimuli are every layer's source term.
  for (int s = 0; s < setup.species_count; ++s) {
    auto pheromone = std::make_unique<OpenCLDiffusionDecay>(compute_, setup.device_domain,
                                                            setup.device_params[static_cast<size_t>(s)],
                                                            settings_.integrator, settings_.time_step, pheromone_options);
    if (!setup.controls.write_rate.empty())
      pheromone->set_write_rate(to_device_order(setup.controls.write_rate, vertex_order_));
    layers_.push_back(std::move(pheromone));
  }
}

void OpenCLAgentSimulation::place_agents() {
  const int agent_count = settings_.agents;
  try {
    compute_.queue.enqueueFillBuffer(deposits_.buffer, cl_uint{0}, 0, deposits_.payload_bytes);
    compute_.queue.enqueueFillBuffer(group_counters_.buffer, cl_uint{0}, 0, group_counters_.payload_bytes);
    compute_.queue.enqueueFillBuffer(first_sensing_.buffer, cl_uint{0}, 0, first_sensing_.payload_bytes);
    if (agent_count > 0) {
      cl::Kernel& k = kernels_->initialise;
      set_arguments(k, constants_, faces_, vertex_parameters_, alias_probability_, alias_index_,
                    spawn_alias_probability_, spawn_alias_index_, spawn_weight_, bias_direction_, device_face_,
                    agents_.buffers());
      compute_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(agent_groups_ * agent_group_),
                                          cl::NDRange(agent_group_));
    }
    compute_.queue.finish();
  } catch (const cl::Error& e) {
    throw device_error("placing " + std::to_string(agent_count) + " agents on " + compute_.device.device_name, e.err());
  }
}

// The agents with a decision due this step, listed and sensed ahead of the agent step
// (kernels/sensing_steering.cl says why).
void OpenCLAgentSimulation::enqueue_sensing() {
  if (settings_.agents == 0) return;
  compute_.queue.enqueueFillBuffer(decider_count_.buffer, cl_uint{0}, 0, decider_count_.payload_bytes);
  cl::Kernel& collect = kernels_->collect_deciders;
  set_arguments(collect, constants_, faces_, vertex_parameters_, agents_.face, agents_.position,
                agents_.time_since_decision, agents_.id, deciders_, decider_count_, cl::Local(2 * sizeof(cl_uint)));
  compute_.queue.enqueueNDRangeKernel(collect, cl::NullRange, cl::NDRange(agent_groups_ * agent_group_),
                                      cl::NDRange(agent_group_));
  cl::Kernel& sense = kernels_->sense_deciders;
  set_arguments(sense, constants_, faces_, vertex_parameters_, sensed_buffer(), read_stimulus_, agents_.face,
                agents_.position, agents_.heading, agents_.id, deciders_, decider_count_, first_sensing_);
  compute_.queue.enqueueNDRangeKernel(sense, cl::NullRange, cl::NDRange(sensing_groups_ * sensing_group_),
                                      cl::NDRange(sensing_group_));
}

void OpenCLAgentSimulation::enqueue_agent_step() {
  if (settings_.agents == 0) return;
  cl::Kernel& k = kernels_->agent_step;
  set_arguments(k, constants_, faces_, vertex_parameters_, sensed_buffer(), read_stimulus_, alias_probability_, alias_index_, spawn_alias_probability_, spawn_alias_index_, spawn_weight_,
                bias_direction_, bias_strength_, device_face_, deposits_, agents_.face, agents_.position, agents_.heading, agents_.age,
                agents_.exposure, agents_.exposure_threshold, agents_.time_since_decision, agents_.accumulated_turn,
                agents_.id, first_sensing_, group_counters_, cl::Local(PHYSARUM_COUNTERS * sizeof(cl_uint)));
  compute_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(step_groups_ * agent_group_),
                                      cl::NDRange(agent_group_));
}

const cl::Buffer& OpenCLAgentSimulation::sensed_buffer() const {
  return species_deposits_.empty() ? layers_[0]->concentration_buffer() : sensed_.buffer;
}

// sensed_s = sum_j m_sj layer_j for every species s (kernels/species.cl), one launch per layer.
void OpenCLAgentSimulation::enqueue_species_sensed_fields() {
  if (species_deposits_.empty() || settings_.agents == 0) return;
  cl::Kernel& k = kernels_->add_layer_to_sensed;
  const size_t group = 64;
  const size_t global = padded_global_size(static_cast<size_t>(std::max(domain_.vertex_count, 1)), group);
  for (size_t j = 0; j < layers_.size(); ++j) {
    set_arguments(k, sensed_, layers_[j]->concentration_buffer(), sensing_matrix_, static_cast<cl_int>(j),
                  static_cast<cl_int>(j == 0 ? 1 : 0));
    compute_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(global), cl::NDRange(group));
  }
}

void OpenCLAgentSimulation::step() {
  try {
    if (sort_interval_ > 0 && steps_taken_ % sort_interval_ == 0) agent_order_->enqueue_sort(agents_);
    constants_.step = static_cast<dev_uint>(steps_taken_);
    enqueue_species_sensed_fields();
    enqueue_sensing();
    enqueue_agent_step();
    // The field model puts the deposits where its scheme needs them (field_model.hpp): each species'
    // layer its own species' cells. Static fields (static_fields_) never advance.
    if (species_deposits_.empty())
      layers_[0]->advance(deposits_, deposit_scale_);
    else
      for (size_t s = 0; s < layers_.size(); ++s) layers_[s]->advance(species_deposits_[s], deposit_scale_);
  } catch (const cl::Error& e) {
    throw device_error("simulation step " + std::to_string(steps_taken_) + " on " + compute_.device.device_name,
                       e.err());
  }
  ++steps_taken_;
}

void OpenCLAgentSimulation::finish() { compute_.queue.finish(); }

OpenCLField& OpenCLAgentSimulation::checked_layer(int index, const char* what) const {
  check_layer_index(index, layer_count(), "opencl simulation", what);
  const size_t i = static_cast<size_t>(index);
  if (i < layers_.size()) return *layers_[i];
  return *static_fields_[i - layers_.size()];
}

OpenCLField& OpenCLAgentSimulation::layer(int index) const { return checked_layer(index, "layer"); }

int OpenCLAgentSimulation::add_static_layer(const IntrinsicVertexData<double>& domain_values) {
  const int index = layer_count();
  check_layer_values(domain_values, domain_.vertex_count, index, "opencl simulation", "add_static_layer");
  static_fields_.push_back(std::make_unique<OpenCLStaticField>(
      compute_, "static field layer " + std::to_string(index), to_device_order(domain_.vertex_mass, vertex_order_),
      to_device_order(domain_values, vertex_order_)));
  return index;
}

IntrinsicVertexData<double> OpenCLAgentSimulation::field_values(int index) const {
  return to_domain_order(checked_layer(index, "field_values").concentration(), vertex_order_);
}

void OpenCLAgentSimulation::set_field(const IntrinsicVertexData<double>& domain_values, int index) {
  OpenCLField& field = checked_layer(index, "set_field");
  check_layer_values(domain_values, domain_.vertex_count, index, "opencl simulation", "set_field");
  field.set_concentration(to_device_order(domain_values, vertex_order_));
}

void OpenCLAgentSimulation::fill_field(double value, int index) {
  OpenCLField& field = checked_layer(index, "fill_field");
  check_layer_value(value, index, "opencl simulation", "fill_field");
  field.fill(value);
}

FieldStatistics OpenCLAgentSimulation::field_statistics(double U, int index) const {
  return checked_layer(index, "field_statistics").statistics(U);
}

// The device keeps faces in its locality order (face_records.hpp); the host sees domain faces.
std::vector<int> OpenCLAgentSimulation::agent_faces() const {
  std::vector<int> faces = agents_.download_faces(compute_);
  for (int& f : faces) f = face_order_.domain_of_device[static_cast<size_t>(f)];
  return faces;
}

Agents OpenCLAgentSimulation::read_agents() const {
  Agents agents = agents_.download(compute_);
  for (int& f : agents.face) f = face_order_.domain_of_device[static_cast<size_t>(f)];
  return agents;
}

void OpenCLAgentSimulation::write_agents(const Agents& agents) {
  Agents on_device = agents;
  for (int& f : on_device.face) {
    if (f < 0 || f >= domain_.face_count)
      throw InputError("opencl simulation: an agent stands on face " + std::to_string(f) + " of " +
                       std::to_string(domain_.face_count));
    f = face_order_.device_of_domain[static_cast<size_t>(f)];
  }
  agents_.upload(compute_, on_device);
}

SimulationCounters OpenCLAgentSimulation::counters() const {
  std::vector<cl_ulong> partial(agent_groups_ * PHYSARUM_COUNTERS);
  compute_.queue.enqueueReadBuffer(group_counters_.buffer, CL_TRUE, 0, partial.size() * sizeof(cl_ulong), partial.data());
  SimulationCounters c;
  for (size_t g = 0; g < agent_groups_; ++g) {
    c.face_crossings += static_cast<long long>(partial[g * PHYSARUM_COUNTERS + PHYSARUM_COUNTER_MOVE_CROSSINGS]);
    c.sensor_face_crossings += static_cast<long long>(partial[g * PHYSARUM_COUNTERS + PHYSARUM_COUNTER_SENSOR_CROSSINGS]);
    c.boundary_hits += static_cast<long long>(partial[g * PHYSARUM_COUNTERS + PHYSARUM_COUNTER_BOUNDARY_HITS]);
    c.respawns += static_cast<long long>(partial[g * PHYSARUM_COUNTERS + PHYSARUM_COUNTER_RESPAWNS]);
  }
  c.agent_steps = steps_taken_ * settings_.agents;
  return c;
}

SimulationState OpenCLAgentSimulation::save_state() const {
  compute_.queue.finish();
  SimulationState state;
  state.steps_taken = steps_taken_;
  state.time = time();
  for (int layer = 0; layer < layer_count(); ++layer) state.layers.push_back(field_values(layer));
  if (settings_.agents > 0) state.agents = read_agents();
  state.counters = counters();
  return state;
}

void OpenCLAgentSimulation::restore_state(const SimulationState& state) {
  check_state_fits(state, layer_count(), domain_.vertex_count, settings_.agents, domain_.face_count, "opencl simulation");
  try {
    compute_.queue.finish();
    for (int layer = 0; layer < layer_count(); ++layer) set_field(state.layers[static_cast<size_t>(layer)], layer);
    if (settings_.agents > 0) write_agents(state.agents);
    // The counters are partial sums per work-group that counters() adds up: the totals go into the
    // first group's slots, so the sum (all anyone reads) is the saved one.
    std::vector<cl_ulong> partial(agent_groups_ * PHYSARUM_COUNTERS, 0);
    partial[PHYSARUM_COUNTER_MOVE_CROSSINGS] = static_cast<cl_ulong>(state.counters.face_crossings);
    partial[PHYSARUM_COUNTER_SENSOR_CROSSINGS] = static_cast<cl_ulong>(state.counters.sensor_face_crossings);
    partial[PHYSARUM_COUNTER_BOUNDARY_HITS] = static_cast<cl_ulong>(state.counters.boundary_hits);
    partial[PHYSARUM_COUNTER_RESPAWNS] = static_cast<cl_ulong>(state.counters.respawns);
    compute_.queue.enqueueWriteBuffer(group_counters_.buffer, CL_TRUE, 0, partial.size() * sizeof(cl_ulong), partial.data());
    // A step leaves the deposit accumulator cleared (the field model empties it); a fresh one is
    // cleared too, so nothing else needs resetting.
  } catch (const cl::Error& e) {
    throw device_error("restoring a saved state on " + compute_.device.device_name, e.err());
  }
  steps_taken_ = state.steps_taken;
}

std::string OpenCLAgentSimulation::device_name() const {
  return compute_.device.platform_name + " / " + compute_.device.device_name + " (" + compute_.device.type + ", " +
         compute_.device.driver_version + ")";
}

std::vector<std::string> OpenCLAgentSimulation::damaged_canaries() const {
  std::vector<std::string> damaged;
  for (const auto& layer : layers_)
    for (const std::string& name : layer->damaged_canaries()) damaged.push_back(name);
  for (const auto& field : static_fields_)
    for (const std::string& name : field->damaged_canaries()) damaged.push_back(name);
  std::vector<const DeviceBuffer*> guarded = agents_.buffers();
  guarded.push_back(&deposits_);
  guarded.push_back(&group_counters_);
  if (!species_deposits_.empty()) guarded.push_back(&sensed_);
  for (const DeviceBuffer* b : {&deciders_, &decider_count_, &first_sensing_}) guarded.push_back(b);
  if (agent_order_)
    for (const DeviceBuffer* b : agent_order_->written_buffers()) guarded.push_back(b);
  for (const DeviceBuffer* b : guarded)
    if (!canary_intact(compute_, *b)) damaged.push_back(b->name);
  return damaged;
}

}  // namespace physarum::opencl
