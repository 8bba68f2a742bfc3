#include "common/setup/cached_map_evaluation.hpp"

#include "common/base/content_hash.hpp"
#include "common/maps/inline_maps.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>

namespace physarum {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The hash of the triangulation the maps are evaluated on: the input geometry the intrinsic vertices
// are located on, and the intrinsic faces with their layouts (which carry the edge lengths).
std::uint64_t triangulation_hash(const PreparedSurface& surface) {
  ContentHasher h;
  const InputMesh& input = surface.input;
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double) && sizeof(std::array<Eigen::Vector2d, 3>) == 6 * sizeof(double),
                "positions and layouts are hashed as packed doubles");
  h.add_array(std::span<const Eigen::Vector3d>(input.positions));
  h.add_array(std::span<const std::array<int, 3>>(input.triangles));
  const SurfaceDomain& domain = surface.domain;
  h.add_array(std::span<const std::array<int, 3>>(domain.face_vertices));
  h.add_array(std::span<const std::array<Eigen::Vector2d, 3>>(domain.face_corners));
  // Field by field: SurfacePoint has padding between its int and its doubles.
  for (const SurfacePoint& p : domain.vertex_location) {
    h.add_bytes(&p.face, sizeof p.face);
    h.add_bytes(p.barycentric.data(), 3 * sizeof(double));
  }
  return h.digest();
}

json surface_key(const SurfaceSpec& spec, const PreparedSurface& surface) {
  json key;
  std::error_code ec;
  // A mesh file by its content (the same bytes elsewhere share entries); a built-in shape by name.
  if (fs::is_regular_file(spec.mesh, ec))
    key["mesh_xxh3"] = hex64(file_content_hash(spec.mesh));
  else
    key["mesh"] = spec.mesh;
  key["scale_to_area"] = spec.scale_to_area ? json(*spec.scale_to_area) : json();
  key["max_circumradius"] = spec.max_circumradius ? json(*spec.max_circumradius) : json();
  key["min_angle_deg"] = spec.min_angle_deg;
  key["triangulation_xxh3"] = hex64(triangulation_hash(surface));
  key["intrinsic_vertices"] = surface.domain.vertex_count;
  key["intrinsic_faces"] = surface.domain.face_count;
  return key;
}

// Every string anywhere in `value` (object values, array elements, nested).
void strings_in(const json& value, std::vector<std::string>& out) {
  if (value.is_string()) out.push_back(value.get<std::string>());
  if (value.is_structured())
    for (const json& item : value) strings_in(item, out);
}

// The maps `definition` reads: its declared dependencies, and any string of its JSON naming another
// map of the set (so a source kind whose dependencies() misses a name still re-keys with it).
std::vector<std::string> maps_read(const MapDefinition& definition, const json& given, const MapSet& maps) {
  std::set<std::string> names;
  for (const std::string& d : definition.dependencies()) names.insert(d);
  std::vector<std::string> strings;
  strings_in(given, strings);
  for (const std::string& s : strings)
    if (s != definition.name && maps.find(s) != nullptr) names.insert(s);
  return {names.begin(), names.end()};
}

// The files `definition` names, resolved: every source's `path` member, and every string of its JSON
// that names an existing file relative to `folder` (or absolutely).
std::set<std::string> files_named(const MapDefinition& definition, const json& given, const std::string& folder) {
  std::set<std::string> files;
  std::visit(
      [&](const auto& s) {
        if constexpr (requires { s.path; }) files.insert(fs::path(s.path).lexically_normal().string());
      },
      definition.source);
  std::vector<std::string> strings;
  strings_in(given, strings);
  for (const std::string& s : strings) {
    if (s.empty()) continue;
    fs::path path(s);
    if (path.is_relative()) path = fs::path(folder) / path;
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) files.insert(path.lexically_normal().string());
  }
  return files;
}

}  // namespace

MapSources map_sources_of(const Scene& scene) {
  const std::string folder = scene.source.empty() ? std::string(".") : fs::path(scene.source).parent_path().string();
  return MapSources{scene.maps, scene.maps_given, folder.empty() ? std::string(".") : folder, surface_spec(scene),
                    scene.source.empty() ? std::string("scene") : scene.source};
}

std::string MapEvaluationReport::summary() const {
  std::string line = "maps: ";
  if (!from_cache.empty()) line += std::to_string(from_cache.size()) + " from cache";
  if (!computed.empty()) line += std::string(from_cache.empty() ? "" : ", ") + std::to_string(computed.size()) + " computed";
  if (from_cache.empty() && computed.empty()) line += "none";
  char time[32];
  std::snprintf(time, sizeof time, ", %.3g s", seconds);
  line += time;
  line += cache_folder.empty() ? std::string(" (cache off)") : " (cache: " + cache_folder + ")";
  return line;
}

std::map<std::string, MapCacheKey> map_cache_keys(const MapSources& sources, const PreparedSurface& surface) {
  std::map<std::string, MapCacheKey> keys;
  if (sources.maps.empty() || !sources.given.is_object()) return keys;
  // The definitions as parse_maps saw them: inline ones hoisted to maps of their own, with the same
  // names (common/maps/inline_maps.hpp), so each is keyed, cached and found like a named map.
  const json named = with_inline_maps_named(sources.given);
  const json surface_part = surface_key(sources.surface, surface);
  std::map<std::string, std::uint64_t> file_hashes;  // each file hashed once
  for (const MapDefinition& m : sources.maps.in_dependency_order()) {
    const auto given = named.find(m.name);
    if (given == named.end()) continue;
    json key;
    key["format"] = MapCache::kFormatVersion;
    key["build_xxh3"] = hex64(executable_hash());
    key["surface"] = surface_part;
    key["kind"] = to_string(m.kind);
    key["definition"] = *given;
    json files = json::object();
    for (const std::string& path : files_named(m, *given, sources.folder)) {
      auto [it, fresh] = file_hashes.emplace(path, 0);
      if (fresh) it->second = file_content_hash(path);
      files[path] = hex64(it->second);
    }
    key["files"] = files;
    json reads = json::object();
    bool keyed = true;
    for (const std::string& name : maps_read(m, *given, sources.maps)) {
      const auto dependency = keys.find(name);
      if (dependency == keys.end()) {
        keyed = false;  // reads a map without a key: its values cannot be vouched for
        break;
      }
      reads[name] = hex64(dependency->second.hash);
    }
    if (!keyed) continue;
    key["reads"] = reads;
    // nlohmann::json keeps object keys sorted: dump() is canonical.
    keys.emplace(m.name, MapCacheKey::of(key.dump()));
  }
  return keys;
}

EvaluatedMaps cached_evaluate_maps(const MapSources& sources, const PreparedSurface& surface, const MapCache& cache,
                                   MapEvaluationReport* report) {
  MapEvaluationReport local;
  MapEvaluationReport& r = report ? *report : local;
  r = MapEvaluationReport{};
  const auto start = std::chrono::steady_clock::now();
  struct Clock {  // stops the clock however the call returns
    MapEvaluationReport& r;
    std::chrono::steady_clock::time_point start;
    ~Clock() { r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }
  } clock{r, start};
  if (!cache.enabled() || sources.maps.empty()) {
    for (const MapDefinition& m : sources.maps.in_dependency_order()) r.computed.push_back(m.name);
    return evaluate_maps(sources.maps, surface, sources.where);
  }
  r.cache_folder = (cache.folder() / "maps").string();
  const std::map<std::string, MapCacheKey> keys = map_cache_keys(sources, surface);
  auto note_rejected = [&](const std::string& name, const MapCacheKey& key, const std::string& why) {
    if (!why.empty())
      r.notes.push_back("map cache: entry " + cache.entry_path(key).string() + " of map '" + name + "' ignored (" + why +
                        "); recomputed");
  };

  EvaluatedMaps result;
  std::set<std::string> missing;
  for (const MapDefinition& m : sources.maps.in_dependency_order()) {
    const auto key = keys.find(m.name);
    if (key == keys.end()) {
      missing.insert(m.name);
      continue;
    }
    if (m.kind == MapKind::Scalar) {
      auto found = cache.load_scalar(key->second, surface.domain.vertex_count);
      note_rejected(m.name, key->second, found.rejected);
      if (found.values) result.scalar.emplace(m.name, std::move(*found.values));
      else missing.insert(m.name);
    } else {
      auto found = cache.load_vector(key->second, surface.domain.face_count);
      note_rejected(m.name, key->second, found.rejected);
      if (found.values) result.vector.emplace(m.name, std::move(*found.values));
      else missing.insert(m.name);
    }
  }
  if (missing.empty()) {
    for (const MapDefinition& m : sources.maps.in_dependency_order()) r.from_cache.push_back(m.name);
    return result;
  }

  // Only the missing maps are computed; the cached ones they read are handed over as they are.
  result = evaluate_maps(sources.maps, surface, sources.where, std::move(result));
  for (const MapDefinition& m : sources.maps.in_dependency_order()) {
    if (!missing.count(m.name)) {
      r.from_cache.push_back(m.name);
      continue;
    }
    r.computed.push_back(m.name);
    const auto key = keys.find(m.name);
    if (key == keys.end()) continue;
    const std::string problem = m.kind == MapKind::Scalar ? cache.store_scalar(key->second, result.scalar.at(m.name))
                                                          : cache.store_vector(key->second, result.vector.at(m.name));
    if (!problem.empty()) r.notes.push_back("map cache: map '" + m.name + "' not stored: " + problem);
  }
  return result;
}

}  // namespace physarum
