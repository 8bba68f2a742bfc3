#include "api/backend_factory.hpp"

#include "api/models/model_table.hpp"

#include "common/setup/agent_inputs.hpp"
#include "common/base/errors.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/setup/reaction_diffusion_build.hpp"
#include "reference/agents.hpp"
#include "reference/reaction_diffusion.hpp"
#include "opencl/reaction_diffusion.hpp"
#include "reference/agent_simulation.hpp"

#include "opencl/runtime/opencl_api.hpp"

#include <algorithm>

namespace physarum {
namespace {

template <class Vector>
constexpr double element_bytes() {
  return static_cast<double>(sizeof(typename Vector::value_type));
}

// The reference's Agents SoA (reference/agents.hpp): one element of each array per agent.
constexpr double kReferenceAgentBytes =
    element_bytes<decltype(Agents::face)>() + element_bytes<decltype(Agents::position)>() +
    element_bytes<decltype(Agents::heading)>() + element_bytes<decltype(Agents::age)>() +
    element_bytes<decltype(Agents::exposure)>() + element_bytes<decltype(Agents::exposure_threshold)>() +
    element_bytes<decltype(Agents::time_since_decision)>() + element_bytes<decltype(Agents::accumulated_turn)>();

// The OpenCL agent buffers (opencl/agents.cpp): face, position, heading, five floats and an id per
// agent; the simulation keeps a second, sorted copy (opencl/agent_simulation.cpp) and one decider slot.
constexpr double kOpenCLAgentBufferBytes = sizeof(cl_int) + 2 * sizeof(cl_float2) + 5 * sizeof(cl_float) + sizeof(cl_uint);
constexpr double kOpenCLAgentBytes = 2 * kOpenCLAgentBufferBytes + sizeof(cl_uint);
// The largest single agent buffer: positions or headings.
constexpr double kOpenCLLargestAgentBuffer = sizeof(cl_float2);

// Per vertex: the backends' fields and parameters (concentration, deposits, per-vertex parameters,
// mass, the forward-Euler matrix's rows) — about 16 doubles; per face: a 64-byte device face record
// or the reference's face arrays read in place (the domain itself is already allocated).
constexpr double kVertexBytes = 16 * sizeof(double);
constexpr double kFaceBytes = 64;

}  // namespace

std::optional<opencl::ComputeContext> compute_context_for(BackendChoice backend, const std::string& device_spec) {
  if (backend != BackendChoice::OpenCL) return std::nullopt;
  return opencl::make_compute_context(device_spec);
}

MemoryNeed estimate_memory(BackendChoice backend, const SurfaceDomain& domain, int agents) {
  MemoryNeed need;
  const double n = std::max(agents, 0);
  const double surface = kVertexBytes * domain.vertex_count + kFaceBytes * domain.face_count;
  if (backend == BackendChoice::Reference) {
    need.host_bytes = kReferenceAgentBytes * n + surface;
    need.breakdown = format_number(kReferenceAgentBytes) + " B per agent x " + format_number(n) + " agents + " +
                     format_bytes(surface) + " for the surface";
  } else {
    need.host_bytes = surface;
    need.device_bytes = kOpenCLAgentBytes * n + surface;
    need.largest_device_buffer = std::max(kOpenCLLargestAgentBuffer * n, kFaceBytes * domain.face_count);
    need.breakdown = format_number(kOpenCLAgentBytes) + " B per agent on the device x " + format_number(n) +
                     " agents + " + format_bytes(surface) + " for the surface";
  }
  return need;
}

std::unique_ptr<SimulationBackend> make_backend(BackendChoice backend, const opencl::ComputeContext* compute,
                                                const SurfaceDomain& domain, const Scene& scene, const SceneArrays& arrays,
                                                const opencl::OpenCLBackendOptions& options) {
  // scene.agent_model() refuses a scene of another model (make_backend with a PreparedSurface builds any model's).
  const bool competing_species = !arrays.species.species.empty() && !arrays.species.is_single();
  const MemoryNeed need = estimate_memory(backend, domain, scene.agent_model().agents);
  if (backend == BackendChoice::Reference) {
    check_memory(scene.source, need, available_host_memory_bytes());
    if (competing_species)
      return std::make_unique<ReferenceAgentSimulation>(domain, arrays.species, arrays.controls, simulation_settings(scene));
    return std::make_unique<ReferenceAgentSimulation>(domain, arrays.parameters, arrays.controls, simulation_settings(scene));
  }
  if (!compute) throw UsageError("the OpenCL backend needs a compute context");
  check_memory(scene.source, need, available_host_memory_bytes(), compute->device.device_name,
               static_cast<double>(compute->device.global_memory_bytes),
               static_cast<double>(compute->device.max_allocation_bytes));
  if (competing_species)
    return std::make_unique<opencl::OpenCLAgentSimulation>(*compute, domain, arrays.species, arrays.controls,
                                                      simulation_settings(scene), options);
  return std::make_unique<opencl::OpenCLAgentSimulation>(*compute, domain, arrays.parameters, arrays.controls,
                                                    simulation_settings(scene), options);
}

std::unique_ptr<SimulationBackend> make_backend(BackendChoice backend, const opencl::ComputeContext* compute,
                                                const PreparedSurface& surface, const Scene& scene,
                                                const opencl::OpenCLBackendOptions& options) {
  const ModelEntry& model = model_entry(scene);
  if (!model.backend_on) throw InputError(scene.source + ": " + model.why_no_backend_on);
  return model.backend_on(backend, compute, surface, scene, options);
}

std::unique_ptr<SimulationBackend> make_reaction_diffusion_backend(BackendChoice backend,
                                                                   const opencl::ComputeContext* compute,
                                                                   const SurfaceDomain& domain,
                                                                   ReactionDiffusionSystem system,
                                                                   const opencl::OpenCLBackendOptions& options) {
  // Per vertex: the morphogens, their reaction terms and the stiffness rows (about 7 entries of 12
  // bytes per morphogen), checked like the agent model's surface; the device holds them in float.
  const double vertices = static_cast<double>(system.mass.size());
  MemoryNeed need;
  need.host_bytes = vertices * static_cast<double>(system.morphogens.size()) * (3 * sizeof(double) + 7 * 12.0);
  need.breakdown = format_bytes(need.host_bytes) + " for " + format_number(vertices) + " vertices x " +
                   std::to_string(system.morphogens.size()) + " morphogens";
  check_memory("reaction-diffusion", need, available_host_memory_bytes());
  if (backend == BackendChoice::Reference) return std::make_unique<ReferenceReactionDiffusion>(std::move(system));
  if (!compute) throw std::logic_error("make_reaction_diffusion_backend: the OpenCL backend needs a compute context");
  opencl::OpenCLReactionDiffusionOptions rd;
  rd.build_options = options.build_options;
  return std::make_unique<opencl::OpenCLReactionDiffusion>(*compute, domain, system, rd);
}

ChosenBackend choose_backend(const std::string& requested, const std::string& device) {
  ChosenBackend a;
  if (requested != "auto") {
    a.backend = parse_backend_choice(requested);
    a.compute = compute_context_for(a.backend, device);
    return a;
  }
  const bool asked_for_a_device = !device.empty() || std::getenv("PHYSARUM_DEVICE") != nullptr;
  try {
    a.compute = opencl::make_compute_context(device);
    a.backend = BackendChoice::OpenCL;
    a.why = a.compute->device.device_name;
  } catch (const DeviceError& e) {
    if (asked_for_a_device) throw;
    a.backend = BackendChoice::Reference;
    a.why = std::string("no OpenCL device: ") + e.what();
  }
  return a;
}

std::unique_ptr<SimulationBackend> make_backend(const Workload& workload, SurfaceCache& surfaces,
                                                const opencl::ComputeContext* compute,
                                                const opencl::OpenCLBackendOptions& options) {
  return make_backend(workload.backend, compute, surfaces.get(workload.surface), workload.scene, options);
}

}  // namespace physarum
