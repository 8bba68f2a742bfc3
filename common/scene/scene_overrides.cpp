#include "common/scene/scene_overrides.hpp"

#include "common/base/errors.hpp"

#include <charconv>
#include <optional>
#include <vector>

namespace physarum {
namespace {

std::vector<std::string> key_parts(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

std::optional<std::size_t> list_index(const std::string& part) {
  std::size_t index = 0;
  const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), index);
  if (error != std::errc() || end != part.data() + part.size()) return std::nullopt;
  return index;
}

std::string trim(const std::string& s) {
  const std::size_t first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

}  // namespace

void apply_scene_overrides(nlohmann::json& scene, const nlohmann::json& overrides, const std::string& source) {
  if (!overrides.is_object()) throw InputError(source + ": scene overrides must be a JSON object");
  for (auto it = overrides.begin(); it != overrides.end(); ++it) {
    const std::string& key = it.key();
    const std::vector<std::string> parts = key_parts(key);
    nlohmann::json* at = &scene;
    std::string walked;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const std::string& part = parts[i];
      if (part.empty()) throw InputError(source + ": override key '" + key + "' has an empty part");
      if (at->is_array()) {
        const std::optional<std::size_t> index = list_index(part);
        if (!index || *index >= at->size())
          throw InputError(source + ": override key '" + key + "': '" + walked + "' is a list of " +
                           std::to_string(at->size()) + ", '" + part + "' is not an index into it");
        at = &(*at)[*index];
      } else if (at->is_object() || at->is_null()) {
        // A missing object on the way is created (null becomes an object on first member access).
        at = &(*at)[part];
      } else {
        throw InputError(source + ": override key '" + key + "': '" + walked + "' is a " + at->type_name() +
                         ", it has no member '" + part + "'");
      }
      walked += (walked.empty() ? "" : ".") + part;
    }
    *at = it.value();
  }
}

nlohmann::json parse_scene_value(const std::string& text) {
  nlohmann::json parsed = nlohmann::json::parse(text, nullptr, false);
  return parsed.is_discarded() ? nlohmann::json(text) : parsed;
}

std::pair<std::string, nlohmann::json> parse_scene_assignment(const std::string& text, const std::string& flag) {
  const std::size_t eq = text.find('=');
  const std::string key = trim(text.substr(0, eq)), value = eq == std::string::npos ? "" : trim(text.substr(eq + 1));
  if (eq == std::string::npos || key.empty() || value.empty())
    throw UsageError(flag + " '" + text + "': expected KEY=VALUE (KEY may be nested: maps.ramp.range=[0.5,1.5])");
  return {key, parse_scene_value(value)};
}

}  // namespace physarum
