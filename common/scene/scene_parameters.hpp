#pragma once
// A Table-1 parameter as a scene states it: a number in the key's file units (null: +infinity where
// the key allows it), or a map.
#include "common/model/model_parameters.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace physarum {

// A model parameter given by a map: {"map": NAME, "range": [lo, hi]} or a bare NAME. With a range
// the map's values 0..1 are remapped linearly to lo..hi (lo + (hi - lo) * value); without one the
// map's values are the parameter's values in the scene file's units (degrees, m/s, ...).
struct ParameterMap {
  std::string map;
  std::optional<std::array<double, 2>> range;  // {lo, hi}, file units
};

// The parameter `p` of `object` when it is given by a map: a bare map name, or {"map": NAME,
// "range": [lo, hi]} whose bounds are in the parameter's range (so every map value in 0..1 gives an
// allowed value). nullopt for a number (or null, or absent): the ordinary readers take those.
// `key` names it in messages: p.key at the top level, "species[i].key" inside a species entry.
std::optional<ParameterMap> read_parameter_map(const nlohmann::json& object, const ParameterSpec& p,
                                              const std::string& source, std::string_view key);

}  // namespace physarum
