#include "common/map_tools/geodesic_distance_source.hpp"

#include "common/base/errors.hpp"

#include <cmath>

namespace physarum {

using nlohmann::json;

GeodesicDistanceSource parse_geodesic_distance_source(const json& object, const std::string& where) {
  auto fail = [&](const std::string& problem) { throw InputError(where + ": " + problem); };
  const json& inner = object.at("geodesic_distance");
  if (!inner.is_object() || !inner.contains("from"))
    fail("\"geodesic_distance\" = " + inner.dump() + " must be an object with \"from\" (a seed set)");
  for (auto it = inner.begin(); it != inner.end(); ++it)
    if (it.key() != "from" && it.key() != "method" && it.key() != "time_factor")
      fail("\"geodesic_distance\": unknown field \"" + it.key() + "\" (it takes \"from\", \"method\", \"time_factor\")");
  // "method" and "time_factor" beside the source or inside it.
  auto option = [&](const char* key) -> const json* {
    if (inner.contains(key) && object.contains(key))
      fail(std::string("\"") + key + "\" is given both inside and beside \"geodesic_distance\"; give it once");
    if (inner.contains(key)) return &inner.at(key);
    if (object.contains(key)) return &object.at(key);
    return nullptr;
  };

  GeodesicDistanceSource source;
  source.from = parse_seed_set(inner.at("from"), where + ": \"from\"");
  if (const json* method = option("method")) {
    if (*method == "heat")
      source.method = GeodesicMethod::Heat;
    else if (*method == "fmm")
      source.method = GeodesicMethod::FastMarching;
    else
      fail("\"method\" = " + method->dump() + " must be \"heat\" (the heat method) or \"fmm\" (fast marching)");
  }
  if (const json* factor = option("time_factor")) {
    if (source.method != GeodesicMethod::Heat) fail("\"time_factor\" applies to the heat method only, not to \"fmm\"");
    if (!factor->is_number() || !std::isfinite(factor->get<double>()) || !(factor->get<double>() > 0.0))
      fail("\"time_factor\" = " + factor->dump() + " must be a number > 0 (the heat time is time_factor x mean edge length^2)");
    source.time_factor = factor->get<double>();
  }
  return source;
}

}  // namespace physarum
