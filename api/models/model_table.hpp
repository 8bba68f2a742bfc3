#pragma once
// The table of models: everything the library does differently for one model, said once, in one
// entry — the surface it simulates on and its fail-fast checks, its backend (for a Session and on a
// surface the caller brings), its run front end (api/run/), its run length when it fixes its own, and
// what `physarum compare` measures on it. The places that used to branch on the model (Session,
// make_backend, prepare_feasible_surface, prepare_run, run_length_in_steps, compare) ask the table.
//
// A model is registered once, in api/models/model_table.cpp; its scene part is one alternative of
// SceneModel (common/scene/scene_models.hpp). docs/library.md ("A new model") gives the recipe.
#include "api/backend_factory.hpp"
#include "api/feasible_surface.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/agent_inputs.hpp"
#include "common/simulation/simulation_backend.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

class GrowthSimulation;     // api/growth_simulation.hpp
class PreparedRun;          // api/run/prepared_run.hpp
struct RunOptions;          // api/run/run_options.hpp
struct ResumePoint;         // api/run/resume_point.hpp
struct SessionOptions;      // api/session.hpp
struct ComparisonModel;     // api/compare/comparison_model.hpp

// A model's backend as a Session holds it, built on the session's surface and maps.
struct ModelBackend {
  Scene scene;  // the scene as simulated (the agent model: a mapped parameter holds its area mean)
  std::optional<SceneArrays> arrays;  // the agent model's per-vertex inputs
  std::unique_ptr<SimulationBackend> backend;
  GrowthSimulation* growth = nullptr;     // the backend, when it grows its own sheet
  std::vector<std::string> layer_names;   // the dynamic layers, in order
  int preview_layer = 0;                  // the layer a picture shows
  int substeps = 1;                       // explicit sub-steps per step
};

using Say = SurfaceNote;  // a line for the user; may be empty (quiet)

struct ModelEntry {
  // How messages name the model: "the agent model", "a reaction-diffusion system", "the growth model".
  std::string name;

  // ---- the surface and the fail-fast checks (prepare_feasible_surface) ----
  // The surface it simulates on.
  PreparedSurface (*surface)(const Scene& scene, const Say& say) = nullptr;
  // Checks that need no surface (a bad time step is cheaper to refuse than a refinement to wait
  // for); may be null.
  void (*check_before_surface)(const Scene& scene, const Say& say) = nullptr;
  // Checks on the surface and the maps for a run of `steps` steps; may be null.
  void (*check_on_surface)(const Scene& scene, const FeasibleSurface& feasible, long long steps, const Say& say) = nullptr;

  // ---- the backend ----
  // For a Session, on the session's surface and maps.
  ModelBackend (*build)(const Scene& scene, const FeasibleSurface& feasible, const ChosenBackend& chosen,
                        const SessionOptions& options) = nullptr;
  // On a surface the caller brings (make_backend with a PreparedSurface); null: refused, saying why.
  std::unique_ptr<SimulationBackend> (*backend_on)(BackendChoice backend, const opencl::ComputeContext* compute,
                                                   const PreparedSurface& surface, const Scene& scene,
                                                   const opencl::OpenCLBackendOptions& options) = nullptr;
  std::string why_no_backend_on;

  // ---- live changes (Session::set, Python's Simulation.set, the studio) ----
  // Applies `key` = `value` (a --set path) to the scene a running session was built from, when the
  // model takes that key on the fly; InputError naming the key when it needs a new run, or for a bad
  // value. Null: the model takes no key on the fly.
  void (*set_on_the_fly)(Scene& scene, const std::string& key, const nlohmann::json& value) = nullptr;

  // ---- `physarum run` (api/run/) ----
  std::unique_ptr<PreparedRun> (*prepare_run)(const Scene& scene, const RunOptions& options, long long steps,
                                              const std::optional<ResumePoint>& resume) = nullptr;
  // The run length when the model fixes its own (the growth model: its schedule), checking the
  // options against it; null: --steps, --sim-time, the scene's steps or sim_time.
  long long (*own_run_length)(const RunOptions& options, const Scene& scene) = nullptr;

  // ---- `physarum compare` ----
  // What the harness measures on it; null: refused before anything runs, saying why.
  const ComparisonModel* comparison = nullptr;
  std::string why_not_compared;
};

// The entry of the scene's model.
const ModelEntry& model_entry(const Scene& scene);


}  // namespace physarum
