#include "api/feasible_surface.hpp"

#include "common/model/agent_model.hpp"
#include "common/setup/growing_sheet_surface.hpp"
#include "common/setup/run_feasibility.hpp"
#include "common/setup/scene_maps.hpp"

#include <iostream>
#include <string>
#include <unistd.h>

namespace physarum {

// About ten seconds of work and more (1e9 elementary operations a second at best).
constexpr double kLongRunOperations = 1e10;

FeasibleSurface prepare_feasible_surface(const Scene& given, long long steps, const MapCache& cache, const SurfaceNote& note) {
  auto say = [&](const std::string& line) {
    if (note) note(line);
  };
  // Without parameter maps the time scales are known before the surface: checked first, as a bad
  // time step is cheaper to refuse than a refinement is to wait for.
  const bool agents = is_agent_model(given);  // another model's time scales are its own (a reaction's: substeps)
  const bool mapped = has_parameter_maps(given);
  auto check_scales = [&](const Scene& scene) {
    for (const std::string& w : check_time_scales(scene, kMaxTurnDecisionsPerStep)) say("physarum: warning: " + w);
  };
  if (agents && !mapped) check_scales(given);
  FeasibleSurface feasible;
  // A growth scene simulates on its mesh's own triangles at rest (common/setup/growing_sheet_surface.hpp).
  feasible.surface = is_growth(given) ? sheet_surface(initial_sheet(given), given.mesh) : prepare_scene_surface(given, say);
  const PreparedSurface& surface = feasible.surface;
  for (const std::string& w : surface.warnings) say("physarum: warning: " + w);
  feasible.maps = cached_evaluate_maps(map_sources_of(given), surface, cache, &feasible.maps_report);
  if (!agents) return feasible;
  const Scene scene =
      mapped ? with_mean_parameters(given, vertex_parameters(given, surface, feasible.maps), surface.domain) : given;
  if (mapped) check_scales(scene);
  const WorkEstimate work = estimate_work(scene, surface.domain, surface.diameter, steps, kMaxTurnDecisionsPerStep);
  // On a terminal always; in a log only for a long run (a quiet log stays empty on a short one).
  if (::isatty(STDERR_FILENO) == 1 || work.operations >= kLongRunOperations) say(work.describe());
  check_work(scene, work);
  return feasible;
}

}  // namespace physarum
