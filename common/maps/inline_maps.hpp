#pragma once
// Map definitions written inline where a map name is expected, so a scene can compose the map tools
// in one expression: "toward_stem": {"gradient": {"geodesic_distance": {"from": "stem"}},
// "normalize": true}. Before the maps are parsed, every inline definition becomes a named map of its
// own (named after where it was written: "toward_stem_gradient", then "toward_stem_gradient_from",
// with "_2", "_3", ... when that name is taken) and the place that held it names it instead. So the
// rest of the map machinery (dependency order, kinds, evaluation, the cache, maps.ply) sees only
// named maps, and an inline map is evaluated, cached and written like any other.
//
// The places that take a map: the operand of "map" (with "range"), "invert", "threshold", "clamp",
// "diffuse", "slope" and "gradient"; every entry of "sum", "product", "min" and "max"; the "region"
// of each "laplace" entry; and the "from" of "geodesic_distance" when it is a map source rather than
// a seed set ({"points"} or {"boundary"}).
#include <string>

#include <nlohmann/json.hpp>

namespace physarum {

// `maps` (a scene's "maps" object) with every inline definition hoisted to a named map. Anything
// that is not an object is returned unchanged, for parse_maps to report.
nlohmann::json with_inline_maps_named(const nlohmann::json& maps);

}  // namespace physarum
