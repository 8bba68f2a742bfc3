#pragma once
// Choosing and building a simulation backend, in one place for the library's session
// (api/session.hpp), the harness, the command line, the benchmark suites and the device check. It
// links both backends, so it lives in api/ (physarum_api), above common/ (which neither backend's
// code may reach into).
// Before anything is allocated it estimates the memory the agents and the surface need on the host
// and on the device and refuses (InputError) what does not fit.
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "common/setup/run_feasibility.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/setup/workload.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/agent_simulation.hpp"

#include <memory>
#include <optional>
#include <string>

namespace physarum {

// The OpenCL context a backend needs: one from `device_spec` for OpenCL, none for the reference.
std::optional<opencl::ComputeContext> compute_context_for(BackendChoice backend, const std::string& device_spec);

// Memory the backend will allocate for `agents` agents on `domain` (an estimate from the element
// sizes of the reference's Agents SoA and of the OpenCL agent buffers; see the .cpp).
MemoryNeed estimate_memory(BackendChoice backend, const SurfaceDomain& domain, int agents);

// Checks memory (check_memory against the host's available memory and, for OpenCL, the device's
// global memory and largest allocation), then builds the backend from the scene's arrays evaluated
// on `surface` (common/setup/scene_maps.hpp: the per-vertex parameters; the controls are evaluated with
// them). `compute` is required for OpenCL.
std::unique_ptr<SimulationBackend> make_backend(BackendChoice backend, const opencl::ComputeContext* compute,
                                                const PreparedSurface& surface, const Scene& scene,
                                                const opencl::OpenCLBackendOptions& options = {});
// The same with the arrays evaluated once beforehand (a harness builds one backend per seed).
std::unique_ptr<SimulationBackend> make_backend(BackendChoice backend, const opencl::ComputeContext* compute,
                                                const SurfaceDomain& domain, const Scene& scene, const SceneArrays& arrays,
                                                const opencl::OpenCLBackendOptions& options = {});

// A reaction-diffusion system's backend (common/setup/reaction_diffusion_build.hpp builds the system from
// a scene, on `domain`): the reference (reference/reaction_diffusion.hpp) or the OpenCL backend
// (opencl/reaction_diffusion.hpp, with `options`' planted faults), after the memory check. The
// make_backend overload from a PreparedSurface takes a reaction-diffusion scene too (it evaluates the
// scene's maps and builds the system) and refuses a growth scene with an InputError (its sheet changes
// between steps: Session builds it); the one from SceneArrays refuses all but the agent model.
std::unique_ptr<SimulationBackend> make_reaction_diffusion_backend(BackendChoice backend,
                                                                   const opencl::ComputeContext* compute,
                                                                   const SurfaceDomain& domain,
                                                                   ReactionDiffusionSystem system,
                                                                   const opencl::OpenCLBackendOptions& options = {});

// The backend a run uses. "auto" takes the OpenCL backend where a device exists and the reference
// otherwise; it falls back only when nobody asked for a device (no `device`, no $PHYSARUM_DEVICE):
// a device that was asked for and is missing stays an error.
struct ChosenBackend {
  BackendChoice backend = BackendChoice::Reference;
  std::optional<opencl::ComputeContext> compute;
  std::string why;  // for "auto": the device found, or why there is none
};
ChosenBackend choose_backend(const std::string& requested, const std::string& device);

// The same for a workload: its surface from `surfaces` (built there once per SurfaceSpec), its scene
// on its backend.
std::unique_ptr<SimulationBackend> make_backend(const Workload& workload, SurfaceCache& surfaces,
                                                const opencl::ComputeContext* compute,
                                                const opencl::OpenCLBackendOptions& options = {});

}  // namespace physarum
