#include "common/scene/scene_parameters.hpp"

#include "common/scene/scene_fields.hpp"

#include <nlohmann/json.hpp>

namespace physarum {

using nlohmann::json;

std::optional<ParameterMap> read_parameter_map(const json& object, const ParameterSpec& p, const std::string& source,
                                              std::string_view key) {
  const auto it = object.find(std::string(p.key));
  if (it == object.end()) return std::nullopt;
  if (it->is_string()) {
    if (it->get<std::string>().empty()) fail_key(source, key, "an empty map name");
    return ParameterMap{it->get<std::string>(), std::nullopt};
  }
  if (!it->is_object()) return std::nullopt;
  for (auto field = it->begin(); field != it->end(); ++field)
    if (field.key() != "map" && field.key() != "range")
      fail_key(source, key, "unknown field \"" + field.key() + "\" (a parameter map is {\"map\": NAME, \"range\": [lo, hi]})");
  const auto name = it->find("map");
  if (name == it->end() || !name->is_string() || name->get<std::string>().empty())
    fail_key(source, key, it->dump() + " needs \"map\": the name of a scalar map");
  ParameterMap map{name->get<std::string>(), std::nullopt};
  if (const auto range = it->find("range"); range != it->end()) {
    if (!range->is_array() || range->size() != 2 || !(*range)[0].is_number() || !(*range)[1].is_number())
      fail_key(source, key, "\"range\" = " + range->dump() + " must be two numbers [lo, hi]");
    map.range = std::array<double, 2>{(*range)[0].get<double>(), (*range)[1].get<double>()};
    for (const double bound : *map.range)
      if (!map_value_range(p).contains(bound))
        fail_key(source, key, "\"range\" = " + range->dump() + ": the bound " + ValueRange::number(bound) + " " +
                                    std::string(p.unit) + " is out of range (" + map_value_range(p).describe() + ")");
  }
  return map;
}

}  // namespace physarum
