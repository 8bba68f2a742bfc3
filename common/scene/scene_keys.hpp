#pragma once
// Every key a scene file may contain, with its type, allowed values, unit and one line of
// documentation: the run settings listed here, and one key per model parameter taken from the
// parameter table (common/model/model_parameters.hpp). The scene parser (common/scene/scene.cpp) accepts
// exactly these keys, and the README's table of scene keys is this list printed as Markdown
// (`physarum scene-keys`; tests/test_parameter_table.cpp keeps the two equal).
#include "common/model/model_parameters.hpp"
#include "common/base/value_range.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace physarum {

enum class KeyKind {
  Number,
  Integer,
  String,
  NumberOrNull,
  StringOrObject,
  Object,          // a JSON object described by allowed_text ("maps", "bias")
  List,            // a JSON list described by allowed_text ("read_stimuli", "write_stimuli")
  NumberOrString,  // a number or a map name ("spawn_weight")
  Boolean,         // true or false ("dilute")
};

struct SceneKey {
  std::string_view name;
  KeyKind kind;
  bool required;
  ValueRange range;               // numbers, in file units
  std::string_view unit;          // in the file
  std::string_view allowed_text;  // strings: the values allowed, as the README shows them
  std::string default_text;       // what an absent optional key means ("" for none)
  std::string_view doc;
  std::optional<Param> parameter;  // set for the model parameters
  // The model parameters may also be a scalar map's name or {"map": NAME, "range": [lo, hi]}
  // (common/scene/scene_controls.hpp, ParameterMap).
  bool accepts_map = false;
};

// In the README's order: the surface, the agents and time step, the named maps, the model parameters
// (table order), the controls of Sec. 3.3, the integrator, seed and run length, the colour map, the differential harness's compare_* keys.
const std::vector<SceneKey>& scene_keys();

// nullptr when `name` is no scene key.
const SceneKey* find_scene_key(std::string_view name);

// The known key a typo most likely meant.
std::string closest_scene_key(std::string_view name);

// The README table: "| key | unit | allowed | |" and one row per key.
std::string scene_keys_markdown();

}  // namespace physarum
