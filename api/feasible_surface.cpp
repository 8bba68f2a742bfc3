#include "api/feasible_surface.hpp"

#include "api/models/model_table.hpp"
#include "common/setup/scene_maps.hpp"

#include <string>

namespace physarum {

FeasibleSurface prepare_feasible_surface(const Scene& scene, long long steps, const MapCache& cache, const SurfaceNote& note) {
  const ModelEntry& model = model_entry(scene);
  if (model.check_before_surface) model.check_before_surface(scene, note);
  FeasibleSurface feasible;
  feasible.surface = model.surface(scene, note);
  for (const std::string& w : feasible.surface.warnings)
    if (note) note("physarum: warning: " + w);
  feasible.maps = cached_evaluate_maps(map_sources_of(scene), feasible.surface, cache, &feasible.maps_report);
  if (model.check_on_surface) model.check_on_surface(scene, feasible, steps, note);
  return feasible;
}

}  // namespace physarum
