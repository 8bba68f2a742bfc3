#pragma once
// The one JSON-field helper every scene reader uses (the shared keys, the agent model, its controls
// and species, reaction–diffusion): reading a key with its type and range checked against the key
// table (common/scene/scene_keys.hpp), reading a value inside a key (a number, a map name, either),
// and one wording for every message: the scene (its file, or "scene" when built in code), the key,
// and what is wrong.
#include "common/base/value_range.hpp"
#include "common/maps/map_definition.hpp"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace physarum {

// Scenes nest objects and arrays at most this deep. Real scenes nest a few levels (a map inside a
// map inside "maps"); a definition nested thousands deep would cost time and memory quadratic in its
// depth (inline maps are hoisted with names that grow with it) before any error could be given.
constexpr int kMaxSceneNesting = 64;

// InputError "WHERE: nested deeper than 64 levels ..." when `value` does; it never descends further
// than that, so any depth is refused at once.
void check_scene_nesting(const nlohmann::json& value, const std::string& where);
[[noreturn]] void fail_nesting(const std::string& where);

// The scene's name in messages: its file, or "scene" for a scene built in code.
std::string scene_where(const std::string& source);

// InputError "SOURCE: key 'KEY': PROBLEM".
[[noreturn]] void fail_key(const std::string& source, std::string_view key, const std::string& problem);

// InputError "SOURCE: key 'KEY' = VALUE is out of range (RANGE)" with the key table's range.
void check_range(const std::string& source, std::string_view key, double file_units_value);
[[noreturn]] void fail_range(const std::string& source, std::string_view key, const std::string& shown_value,
                             const ValueRange& range);

// InputError unless `entry` is an object whose fields are all among `allowed` (the message lists them).
void only_fields(const nlohmann::json& entry, std::initializer_list<const char*> allowed, const std::string& source,
                 std::string_view key);

// An entry of a list key, for messages: "read_stimuli[0]".
std::string entry_name(std::string_view key, size_t index);

// A value inside a key: a finite number; a (non-empty) map name; a number or a scalar map's name.
double field_number(const nlohmann::json& value, const std::string& source, const std::string& key);
std::string field_map_name(const nlohmann::json& value, const std::string& source, const std::string& key);
MapOperand field_operand(const nlohmann::json& value, const std::string& source, const std::string& key);

// The map `name` must exist in `maps` and be of `kind`. `shown_value` (optional) is shown after the
// key, as a number's out-of-range message shows the number.
void check_map_reference(const MapSet& maps, const std::string& source, const std::string& key,
                         const std::string& name, MapKind kind, const std::string& shown_value = {});

// Top-level keys of one scene object, each checked against its entry in the key table: a missing
// required key, a wrong type or a value out of range is an InputError naming the key.
struct SceneReader {
  const nlohmann::json& object;
  const std::string& source;

  // The value, or nullptr when absent (a missing required key throws).
  const nlohmann::json* find(std::string_view key) const;
  // A number; nullopt when absent or null (null is "not given" for optional keys and NumberOrNull).
  std::optional<double> number(std::string_view key) const;
  // An integer; a float with an integral value (1e5) is accepted, 2.5 is not.
  std::optional<long long> integer(std::string_view key) const;
  std::optional<std::string> string(std::string_view key) const;

 private:
  [[noreturn]] void wrong_type(std::string_view key, const nlohmann::json& v, const char* expected) const;
};

}  // namespace physarum
