#include "common/maps/inline_maps.hpp"

#include <set>
#include <string_view>
#include <utility>
#include <vector>

namespace physarum {
namespace {

using nlohmann::json;

// The fields of a map source whose value is a map (a name, a number, or an inline definition).
constexpr std::string_view kOperandFields[] = {"invert", "threshold", "clamp", "diffuse", "slope", "gradient"};
// The fields whose value is a list of maps.
constexpr std::string_view kOperandListFields[] = {"sum", "product", "min", "max"};

// An object in a seed-set position is a seed set, not a map, when it names points or the boundary.
bool is_seed_set(const json& value) { return value.contains("points") || value.contains("boundary"); }

class Hoister {
 public:
  explicit Hoister(const json& maps) {
    for (auto it = maps.begin(); it != maps.end(); ++it) taken_.insert(it.key());
  }

  // Replaces every inline definition inside `definition` (the map `name`) by a new named map, which
  // is itself searched in turn; returns the definitions added, in the order they were met.
  std::vector<std::pair<std::string, json>> hoist(const std::string& name, json& definition) {
    std::vector<std::pair<std::string, json>> added;
    hoist_operands(name, definition, added);
    // `added` grows while it is walked: take each entry out before searching it.
    for (size_t i = 0; i < added.size(); ++i) {
      const std::string owner = added[i].first;
      json inner = std::move(added[i].second);
      hoist_operands(owner, inner, added);
      added[i].second = std::move(inner);
    }
    return added;
  }

 private:
  std::set<std::string> taken_;

  std::string fresh_name(const std::string& stem) {
    std::string name = stem;
    for (int k = 2; taken_.count(name); ++k) name = stem + "_" + std::to_string(k);
    taken_.insert(name);
    return name;
  }

  // `slot` holds an inline definition: move it out under a new name and put the name in its place.
  void take(json& slot, const std::string& stem, std::vector<std::pair<std::string, json>>& added) {
    const std::string name = fresh_name(stem);
    added.emplace_back(name, std::move(slot));
    slot = name;
  }

  void hoist_operands(const std::string& owner, json& object, std::vector<std::pair<std::string, json>>& added) {
    if (!object.is_object()) return;
    auto inline_at = [&](json& slot, const std::string& stem) {
      if (slot.is_object()) take(slot, stem, added);
    };
    if (object.contains("range") && object.contains("map")) inline_at(object["map"], owner + "_map");
    for (std::string_view field : kOperandFields)
      if (const auto it = object.find(std::string(field)); it != object.end()) inline_at(*it, owner + "_" + std::string(field));
    for (std::string_view field : kOperandListFields)
      if (const auto it = object.find(std::string(field)); it != object.end() && it->is_array())
        for (size_t i = 0; i < it->size(); ++i) inline_at((*it)[i], owner + "_" + std::string(field) + "_" + std::to_string(i));
    if (const auto it = object.find("laplace"); it != object.end() && it->is_array())
      for (size_t i = 0; i < it->size(); ++i)
        if ((*it)[i].is_object() && (*it)[i].contains("region"))
          inline_at((*it)[i]["region"], owner + "_region_" + std::to_string(i));
    if (const auto it = object.find("geodesic_distance"); it != object.end() && it->is_object() && it->contains("from")) {
      json& from = (*it)["from"];
      if (from.is_object() && !is_seed_set(from)) take(from, owner + "_from", added);
    }
  }
};

}  // namespace

json with_inline_maps_named(const json& maps) {
  if (!maps.is_object()) return maps;
  Hoister hoister(maps);
  json named = json::object();
  for (auto it = maps.begin(); it != maps.end(); ++it) {
    json definition = it.value();
    std::vector<std::pair<std::string, json>> added = hoister.hoist(it.key(), definition);
    named[it.key()] = std::move(definition);
    for (auto& [name, inline_definition] : added) named[name] = std::move(inline_definition);
  }
  return named;
}

}  // namespace physarum
