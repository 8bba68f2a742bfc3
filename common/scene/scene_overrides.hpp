#pragma once
// Changing a scene's keys from the command line (`physarum run --set KEY=VALUE`, the variants of
// `physarum sweep --vary`, `physarum compare --arm`), nested keys included, before the scene is read
// with its usual checks (common/scene/scene.hpp: load_scene).
//
// The key rule: KEY is split at dots; each part names a member of a JSON object, or, where the value
// reached so far is a list, a 0-based index into it. So
//   turn_rate=90                      replaces the top-level key,
//   maps.ramp.range=[0.5,1.5]         replaces the range of the map named "ramp",
//   bias.strength=40                  replaces the bias's strength,
//   read_stimuli.0.weight=-0.5        replaces the weight of the first read-stimulus.
// Objects missing on the way are created (maps.spot={"axis":"x"} adds a map), list elements are not
// (an index past the end is an error, as is stepping into a number or a string). Scene keys never
// contain dots, so a dotted key is never a top-level name.
#include <nlohmann/json.hpp>

#include <string>
#include <utility>

namespace physarum {

// Applies every key of `overrides` (an object of KEY: value, keys as above) to `scene`, in order.
// Throws InputError naming `source` (the scene file) and the key when a step of the path is not there.
void apply_scene_overrides(nlohmann::json& scene, const nlohmann::json& overrides, const std::string& source);

// Parses "KEY=VALUE" (as --set takes it): VALUE is read as JSON where it parses as JSON (numbers,
// true, null, [0.5, 1.5], {"map": "ramp"}), and otherwise taken as a string (shape:torus). Throws
// UsageError naming `flag` when there is no '=' or KEY or VALUE is empty.
std::pair<std::string, nlohmann::json> parse_scene_assignment(const std::string& text, const std::string& flag);

// VALUE as parse_scene_assignment reads it.
nlohmann::json parse_scene_value(const std::string& text);

}  // namespace physarum
