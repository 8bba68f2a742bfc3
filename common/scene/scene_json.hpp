#pragma once
// A scene's parameters as JSON, in the scene file's own keys and units (degrees for angles): what
// run.json records and what stored harness statistics are checked against. A parameter given by a
// map is recorded as {"map": NAME, "range": [lo, hi] (when given), "mean": its mean over the surface
// (when the scene went through with_mean_parameters, common/setup/scene_maps.hpp)}; the maps and controls
// follow as the file gave them ("maps", "read_stimuli", ..., "boundary"), when the scene has any.
#include "common/scene/scene.hpp"

#include <nlohmann/json.hpp>

namespace physarum {

nlohmann::ordered_json scene_parameters_json(const Scene& scene);

}  // namespace physarum
