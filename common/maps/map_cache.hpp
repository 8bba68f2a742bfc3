#pragma once
// The on-disk cache of evaluated surface maps (the scene's "maps"; common/setup/cached_map_evaluation.hpp
// decides what goes in and under which key). Evaluating a map tool on a large triangulation (a
// geodesic distance, a Laplace solve) takes seconds; a second `run` or `map` of the same scene reads
// the values back instead.
//
// Where: $PHYSARUM_CACHE_DIR, else $XDG_CACHE_HOME/physarum, else ~/.cache/physarum; entries live in
// its maps/ folder (the OpenCL program cache keeps its binaries in the same root, opencl/runtime/program_cache.hpp).
// PHYSARUM_NO_CACHE=1 (any value but "" or "0"), or PHYSARUM_CACHE_DIR=off, turns it off. The folder is
// kept under $PHYSARUM_CACHE_MAX_MB megabytes (default 2048): after a write, the entries used least
// recently (a hit refreshes an entry's time) are removed until it fits.
//
// One file per map, named by the hash of its key, written under a temporary name and renamed:
//   "physarum-map-cache\n"   magic (19 bytes)
//   u32 format version       (kFormatVersion)
//   u64 key length, key text (the whole key, compared on reading: a hash collision is a miss)
//   u8 kind                  0 scalar (one value per intrinsic vertex), 1 vector (two per face)
//   u64 count                intrinsic vertices or faces
//   count x 1 or 2 float64   the values
//   u64 XXH3 checksum        of every byte before it
// little-endian (the machine's own; another byte order reads as corrupt). An entry is used only when
// every part checks out (size, magic, version, key, kind, count, checksum, finite values); anything
// else is a miss, and the recomputed values replace the entry. A cache that cannot be written (a
// read-only folder) costs a note, never a failed run.
#include "common/base/element_data.hpp"
#include "common/maps/map_definition.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace physarum {

struct MapCacheKey {
  std::string text;        // everything the values depend on, as canonical text (JSON)
  std::uint64_t hash = 0;  // content_hash(text): the entry's file name

  static MapCacheKey of(std::string text);
};

// The outcome of one lookup: the values, or why there are none ("" when the entry does not exist;
// otherwise what was wrong with it, for a note).
template <class Values>
struct MapCacheLookup {
  std::optional<Values> values;
  std::string rejected;
};

class MapCache {
 public:
  static constexpr std::uint32_t kFormatVersion = 1;
  static constexpr std::uintmax_t kDefaultMaxBytes = std::uintmax_t{2048} << 20;

  // A cache that never hits and never writes.
  static MapCache disabled();
  // From the environment (see the header comment). Disabled when PHYSARUM_NO_CACHE is set, or when no
  // folder can be named (no HOME). UsageError when PHYSARUM_CACHE_MAX_MB is not a positive integer.
  static MapCache from_environment();
  // Entries under `folder`/maps (created on the first write), at most `max_bytes` in all.
  explicit MapCache(std::filesystem::path folder, std::uintmax_t max_bytes = kDefaultMaxBytes);

  bool enabled() const { return enabled_; }
  const std::filesystem::path& folder() const { return folder_; }
  // The file that holds (or would hold) the entry of `key`.
  std::filesystem::path entry_path(const MapCacheKey& key) const;

  // `count` is the number of intrinsic vertices (scalar) or faces (vector) the surface has now.
  MapCacheLookup<IntrinsicVertexData<double>> load_scalar(const MapCacheKey& key, int count) const;
  MapCacheLookup<IntrinsicFaceData<std::array<double, 2>>> load_vector(const MapCacheKey& key, int count) const;

  // Write (replace) the entry; "" on success, else why it could not be written (for a note).
  std::string store_scalar(const MapCacheKey& key, const IntrinsicVertexData<double>& values) const;
  std::string store_vector(const MapCacheKey& key, const IntrinsicFaceData<std::array<double, 2>>& values) const;

 private:
  MapCache() = default;
  MapCacheLookup<std::vector<double>> load(const MapCacheKey& key, MapKind kind, int count) const;
  std::string store(const MapCacheKey& key, MapKind kind, const double* values, std::size_t count) const;
  void evict_beyond_budget(const std::filesystem::path& keep) const;

  bool enabled_ = false;
  std::filesystem::path folder_;
  std::uintmax_t max_bytes_ = kDefaultMaxBytes;
};

}  // namespace physarum
