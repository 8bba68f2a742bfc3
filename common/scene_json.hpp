#pragma once
// A scene's parameters as JSON, in the scene file's own keys and units (degrees for angles): what
// run.json records and what stored harness statistics are checked against.
#include "common/scene.hpp"

#include <nlohmann/json.hpp>

namespace physarum {

nlohmann::ordered_json scene_parameters_json(const Scene& scene);

}  // namespace physarum
