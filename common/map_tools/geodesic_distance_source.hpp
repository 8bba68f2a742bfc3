#pragma once
// The geodesic distance map source (docs/maps.md), as parsed:
//   {"geodesic_distance": {"from": SEEDS}, "method": "heat" | "fmm", "time_factor": m}
// SEEDS is a seed set (common/map_tools/seed_set.hpp). "method" (default "heat") and "time_factor" (heat only,
// default 1, > 0: t = m h^2) may stand beside "geodesic_distance" or inside it, not both. Computing
// it is common/map_tools/geodesic_distance.hpp.
#include "common/map_tools/seed_set.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace physarum {

enum class GeodesicMethod { Heat, FastMarching };

struct GeodesicDistanceSource {
  SeedSet from;
  GeodesicMethod method = GeodesicMethod::Heat;
  double time_factor = 1.0;  // heat only
  std::vector<std::string> map_dependencies() const { return from.map_dependencies(); }
};

// Parses the whole map object (the one holding "geodesic_distance"); the caller has checked that it
// holds no other keys than "geodesic_distance", "method" and "time_factor". InputError "WHERE: ..."
// for a missing or malformed "from", an unknown method, a time factor <= 0, "time_factor" with
// "fmm", and a key given both inside and beside "geodesic_distance".
GeodesicDistanceSource parse_geodesic_distance_source(const nlohmann::json& object, const std::string& where);

}  // namespace physarum
