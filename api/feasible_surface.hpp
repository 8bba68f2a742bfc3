#pragma once
// The fail-fast checks of a scene that is about to be simulated (common/setup/run_feasibility.hpp), in the
// order a run makes them before writing anything: the time step against the model's
// time scales (warnings, or InputError), the surface (refused before refining when the
// refinement would exceed its budget, announced when it will be long), then the run's work: one
// estimate line (on a terminal, or for a long run), and InputError when a length exceeds the surface or the work is absurd.
#include "common/setup/cached_map_evaluation.hpp"
#include "common/maps/map_cache.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"

namespace physarum {

struct FeasibleSurface {
  PreparedSurface surface;
  // The scene's maps on the surface, evaluated once here through the map cache: a scene with
  // parameter maps needs them for its checks, and the caller builds its backend from them.
  EvaluatedMaps maps;
  MapEvaluationReport maps_report;
};

// A scene of another model than the agents gets its surface and maps only (its time scales are its own).
// A scene with parameter maps is checked with each mapped parameter's mean over the surface
// (with_mean_parameters), so its time-scale checks come after the surface is built.
// Lines for the user (warnings, the surface's progress, the work estimate) go to `note` (none: quiet).
FeasibleSurface prepare_feasible_surface(const Scene& scene, long long steps, const MapCache& cache,
                                         const SurfaceNote& note);

}  // namespace physarum
