#pragma once
// evaluate_maps (common/maps/map_evaluation.hpp) through the on-disk map cache (common/maps/map_cache.hpp): what
// `run`, `compare` and `map` call, so that a second run of a scene does not recompute its maps.
//
// The key of a map says everything its values depend on:
//   the build       the hash of the running executable (another build may compute other values),
//   the surface     the mesh (its file's content hash, or the shape:NAME), scale_to_area,
//                   max_circumradius and min_angle, and a hash of the triangulation actually built
//                   (input positions and triangles, intrinsic faces, their layouts, the intrinsic
//                   vertices' input locations), so a change in the refinement code also misses,
//   the definition  the map's JSON as written, its kind, the content hash of every file it names
//                   (a source's path, or any string of its JSON that names an existing file), and
//                   the keys of the maps it reads (its dependencies, and any string of its JSON that
//                   names another map), recursively: changing a map re-keys every map that reads it.
// The map's own name is not part of the key: two names for one definition share an entry.
//
// Every map is cached, cheap ones too, and a miss computes only the maps missing: the cached maps
// they read are handed to evaluate_maps as known values, so a cheap map over an expensive one (a
// gradient of a geodesic distance whose "normalize" changed) does not recompute the expensive one.
// Inline definitions are keyed as the maps parse_maps hoists them to (common/maps/inline_maps.hpp).
#include "common/maps/map_cache.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace physarum {

// What a set of maps was parsed from: the JSON object of named maps as written, and the folder its
// relative file names resolve against (a scene's folder).
struct MapSources {
  const MapSet& maps;
  const nlohmann::json& given;
  std::string folder;
  SurfaceSpec surface;
  std::string where;  // starts messages (the scene file)
};

// A scene's maps: scene.maps, scene.maps_given, the scene file's folder and surface_spec(scene).
MapSources map_sources_of(const Scene& scene);

// What one cached evaluation did, for the command line's report line.
struct MapEvaluationReport {
  std::vector<std::string> from_cache;  // maps read from the cache
  std::vector<std::string> computed;    // maps evaluated now
  std::vector<std::string> notes;       // entries ignored (corrupt, stale) and entries not written
  std::string cache_folder;             // "" when the cache is off
  double seconds = 0.0;                 // the whole call: keys, lookups, evaluation, stores

  // One line: "maps: 2 from cache, 1 computed, 0.41 s (cache: DIR)", "maps: 3 computed, 0.2 s (cache off)".
  std::string summary() const;
};

// The cache key of every map of `sources` on `surface`, by name. A map whose definition is missing
// from `sources.given` has no key (it is always computed).
std::map<std::string, MapCacheKey> map_cache_keys(const MapSources& sources, const PreparedSurface& surface);

// Every map of `sources.maps` on `surface`, as evaluate_maps gives them: read from `cache` where it
// holds a valid entry, otherwise evaluated (with the maps they read) and stored. Errors are
// evaluate_maps' own; a cache problem is never an error, only a note in `report`.
EvaluatedMaps cached_evaluate_maps(const MapSources& sources, const PreparedSurface& surface, const MapCache& cache,
                                   MapEvaluationReport* report = nullptr);

}  // namespace physarum
