#pragma once
// The library's way in: a scene prepared on its surface (the same checks as `physarum run`), its
// maps evaluated once through the map cache, and the backend of its model built — then step it,
// read and set its fields on the intrinsic or on the input vertices, save and restore it. `physarum
// run` builds every run with it, and the Python module binds it; docs/library.md shows it in use.
//
// The public headers of the library are the ones api/physarum.hpp includes.
#include "api/backend_factory.hpp"
#include "api/feasible_surface.hpp"
#include "api/growth_simulation.hpp"
#include "common/scene/scene.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/prepared_surface.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

struct SessionParts;  // api/session.cpp

struct SessionOptions {
  std::string backend = "auto";  // "auto" | "reference" | "opencl" (choose_backend)
  std::string device;            // an OpenCL device ("" : $PHYSARUM_DEVICE, else the first)
  // The run length the feasibility checks judge (agents: the work estimate); 0 judges one step.
  long long planned_steps = 0;
  bool use_map_cache = true;  // through MapCache::from_environment() (PHYSARUM_NO_CACHE turns it off too)
  SurfaceNote log;            // the user's lines: warnings, the surface's progress, the backend chosen; none: quiet
  opencl::OpenCLBackendOptions opencl;  // planted faults, tuning (the harness's)
};

class Session {
 public:
  // Everything that can refuse the scene happens here (InputError, DeviceError), before any step.
  explicit Session(const Scene& scene, const SessionOptions& options = {});
  ~Session();
  Session(Session&&) noexcept;
  Session& operator=(Session&&) noexcept;

  // The scene as simulated: a mapped agent parameter holds its area mean (what U and run.json use).
  const Scene& scene() const;
  const PreparedSurface& surface() const;
  // The surface the layers lie on now: surface(), or a growth scene's sheet as it has grown.
  const PreparedSurface& surface_now() const;
  const EvaluatedMaps& maps() const;
  const MapEvaluationReport& maps_report() const;
  // The agent model's per-vertex inputs; nullptr for a reaction–diffusion scene.
  const SceneArrays* agent_arrays() const;
  BackendChoice backend_choice() const;
  const std::string& backend_reason() const;  // for "auto": the device found, or why there is none
  SimulationBackend& backend();
  const SimulationBackend& backend() const;

  // The dynamic layers' names in layer order: "pheromone" (competing species: "pheromone_0", ...)
  // or the morphogens' names.
  const std::vector<std::string>& layer_names() const;
  // The layer a picture shows: 0, or the reaction's preview morphogen.
  int preview_layer() const;
  // Explicit sub-steps per step of a reaction–diffusion system (its stability limit); 1 otherwise.
  int substeps() const;
  // A growth scene's simulation (its sheet, its growth records), nullptr for the other models. Its
  // layers live on the sheet as it is now: surface() is the sheet at the start, growth()->surface()
  // the sheet now.
  GrowthSimulation* growth();
  const GrowthSimulation* growth() const;

  void step(long long steps = 1);
  double time() const;
  long long steps_taken() const;
  // A layer per intrinsic vertex, and at the input mesh's vertices (each input vertex is an
  // intrinsic vertex: its value, no interpolation).
  IntrinsicVertexData<double> field(int layer = 0) const;
  InputVertexData<double> field_on_input(int layer = 0) const;
  void set_field(const IntrinsicVertexData<double>& values, int layer = 0);
  // Per input vertex, interpolated onto the intrinsic vertices (input_to_intrinsic).
  void set_field_on_input(const InputVertexData<double>& values, int layer = 0);

  // A live change: `key` (a --set path: "sensor_angle", "parameters.F") takes `value` from the next
  // step on when the model takes it on the fly (its entry's set_on_the_fly, api/models/model_table.hpp:
  // the agent model's Table 1 parameters, a reaction's coefficients); returns the steps taken, the
  // step after which it applies. InputError naming the key when it needs a new run, or for a bad
  // value: nothing changes then. The scene() afterwards is the changed one.
  long long set(const std::string& key, const nlohmann::json& value);

  // A checkpoint file (common/run/checkpoint.hpp); restore refuses one of another build, backend,
  // device or scene, and changes nothing then.
  void save(const std::string& path) const;
  void restore(const std::string& path);

 private:
  std::unique_ptr<SessionParts> parts_;
};

}  // namespace physarum
