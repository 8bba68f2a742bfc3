#include "common/maps/map_cache.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/content_hash.hpp"
#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <system_error>

namespace physarum {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kMagic = "physarum-map-cache\n";
constexpr const char* kEntrySuffix = ".map";

template <class T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// Reads fixed-size fields from an entry's bytes; any read past the end marks it short.
struct Reader {
  std::string_view bytes;
  std::size_t at = 0;
  bool short_read = false;

  template <class T>
  T next() {
    T value{};
    if (bytes.size() - at < sizeof value) {
      short_read = true;
      return value;
    }
    std::memcpy(&value, bytes.data() + at, sizeof value);
    at += sizeof value;
    return value;
  }
  std::string_view take(std::size_t n) {
    if (bytes.size() - at < n) {
      short_read = true;
      return {};
    }
    const std::string_view piece = bytes.substr(at, n);
    at += n;
    return piece;
  }
};

const char* env(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : nullptr;
}

}  // namespace

MapCacheKey MapCacheKey::of(std::string text) {
  MapCacheKey key;
  key.hash = content_hash(text);
  key.text = std::move(text);
  return key;
}

MapCache MapCache::disabled() { return MapCache(); }

MapCache MapCache::from_environment() {
  if (const char* off = env("PHYSARUM_NO_CACHE"); off != nullptr && std::string_view(off) != "0") return disabled();
  std::uintmax_t max_bytes = kDefaultMaxBytes;
  if (const char* limit = env("PHYSARUM_CACHE_MAX_MB")) {
    char* end = nullptr;
    errno = 0;
    const long long mb = std::strtoll(limit, &end, 10);
    if (errno != 0 || end == limit || *end != '\0' || mb < 1 || mb > (1LL << 40))
      throw UsageError(std::string("PHYSARUM_CACHE_MAX_MB=") + limit + " must be a positive whole number of megabytes");
    max_bytes = static_cast<std::uintmax_t>(mb) << 20;
  }
  // "off" as the OpenCL program cache (opencl/runtime/program_cache.hpp) reads it: both share the folder.
  if (const char* dir = env("PHYSARUM_CACHE_DIR")) return std::string_view(dir) == "off" ? disabled() : MapCache(dir, max_bytes);
  if (const char* xdg = env("XDG_CACHE_HOME")) return MapCache(fs::path(xdg) / "physarum", max_bytes);
  if (const char* home = env("HOME")) return MapCache(fs::path(home) / ".cache" / "physarum", max_bytes);
  return disabled();
}

MapCache::MapCache(fs::path folder, std::uintmax_t max_bytes)
    : enabled_(true), folder_(std::move(folder)), max_bytes_(max_bytes) {}

fs::path MapCache::entry_path(const MapCacheKey& key) const { return folder_ / "maps" / (hex64(key.hash) + kEntrySuffix); }

MapCacheLookup<std::vector<double>> MapCache::load(const MapCacheKey& key, MapKind kind, int count) const {
  MapCacheLookup<std::vector<double>> result;
  if (!enabled_) return result;
  const fs::path path = entry_path(key);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return result;
  // Read whole in one call (an entry of a million-vertex map is 8 MB).
  std::string bytes;
  {
    std::FILE* in = std::fopen(path.c_str(), "rb");
    if (in == nullptr) {
      result.rejected = "cannot be opened";
      return result;
    }
    const std::uintmax_t size = fs::file_size(path, ec);
    bytes.resize(ec ? 0 : static_cast<std::size_t>(size));
    bytes.resize(std::fread(bytes.data(), 1, bytes.size(), in));
    std::fclose(in);
  }
  auto reject = [&](const std::string& why) {
    result.rejected = why;
    return result;
  };
  Reader r{bytes};
  if (r.take(kMagic.size()) != kMagic) return reject("not a map cache entry (wrong magic)");
  if (r.next<std::uint32_t>() != kFormatVersion) return reject("another format version");
  const auto key_length = r.next<std::uint64_t>();
  if (r.short_read || key_length > bytes.size()) return reject("truncated");
  if (r.take(static_cast<std::size_t>(key_length)) != key.text) return reject("its key differs (a hash collision)");
  const auto stored_kind = r.next<std::uint8_t>();
  const auto stored_count = r.next<std::uint64_t>();
  if (r.short_read) return reject("truncated");
  if (stored_kind != (kind == MapKind::Scalar ? 0 : 1)) return reject("holds the other kind of map");
  if (stored_count != static_cast<std::uint64_t>(count))
    return reject("holds " + std::to_string(stored_count) + " values for " + std::to_string(count) +
                  (kind == MapKind::Scalar ? " intrinsic vertices" : " intrinsic faces"));
  const std::size_t doubles = static_cast<std::size_t>(count) * (kind == MapKind::Scalar ? 1 : 2);
  const std::size_t payload_at = r.at;
  if (bytes.size() != payload_at + doubles * sizeof(double) + sizeof(std::uint64_t))
    return reject("has " + std::to_string(bytes.size()) + " bytes where " +
                  std::to_string(payload_at + doubles * sizeof(double) + sizeof(std::uint64_t)) + " were expected (truncated)");
  std::uint64_t stored_checksum = 0;
  std::memcpy(&stored_checksum, bytes.data() + bytes.size() - sizeof stored_checksum, sizeof stored_checksum);
  if (content_hash(std::string_view(bytes).substr(0, bytes.size() - sizeof stored_checksum)) != stored_checksum)
    return reject("fails its checksum (corrupt)");
  std::vector<double> values(doubles);
  std::memcpy(values.data(), bytes.data() + payload_at, doubles * sizeof(double));
  if (!std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); }))
    return reject("holds a value that is not finite");
  // A hit is a use: the least recently used entries go first when the folder is over its budget.
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
  result.values = std::move(values);
  return result;
}

MapCacheLookup<IntrinsicVertexData<double>> MapCache::load_scalar(const MapCacheKey& key, int count) const {
  MapCacheLookup<std::vector<double>> raw = load(key, MapKind::Scalar, count);
  MapCacheLookup<IntrinsicVertexData<double>> result;
  result.rejected = std::move(raw.rejected);
  if (raw.values) result.values = IntrinsicVertexData<double>(std::move(*raw.values));
  return result;
}

MapCacheLookup<IntrinsicFaceData<std::array<double, 2>>> MapCache::load_vector(const MapCacheKey& key, int count) const {
  MapCacheLookup<std::vector<double>> raw = load(key, MapKind::Vector, count);
  MapCacheLookup<IntrinsicFaceData<std::array<double, 2>>> result;
  result.rejected = std::move(raw.rejected);
  if (raw.values) {
    IntrinsicFaceData<std::array<double, 2>> vectors(static_cast<std::size_t>(count));
    for (int f = 0; f < count; ++f) vectors[f] = {(*raw.values)[2 * static_cast<std::size_t>(f)], (*raw.values)[2 * static_cast<std::size_t>(f) + 1]};
    result.values = std::move(vectors);
  }
  return result;
}

std::string MapCache::store(const MapCacheKey& key, MapKind kind, const double* values, std::size_t count) const {
  if (!enabled_) return {};
  const fs::path path = entry_path(key);
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) return "cannot create " + path.parent_path().string() + ": " + ec.message();
  const std::size_t doubles = count * (kind == MapKind::Scalar ? 1 : 2);
  std::string bytes;
  bytes.reserve(kMagic.size() + 64 + key.text.size() + doubles * sizeof(double));
  bytes.append(kMagic);
  append(bytes, kFormatVersion);
  append(bytes, static_cast<std::uint64_t>(key.text.size()));
  bytes.append(key.text);
  append(bytes, static_cast<std::uint8_t>(kind == MapKind::Scalar ? 0 : 1));
  append(bytes, static_cast<std::uint64_t>(count));
  bytes.append(reinterpret_cast<const char*>(values), doubles * sizeof(double));
  append(bytes, content_hash(bytes));
  try {
    write_text_file_atomically(path.string(), bytes);
  } catch (const InputError& e) {
    return e.what();
  }
  evict_beyond_budget(path);
  return {};
}

std::string MapCache::store_scalar(const MapCacheKey& key, const IntrinsicVertexData<double>& values) const {
  return store(key, MapKind::Scalar, values.data(), values.size());
}

std::string MapCache::store_vector(const MapCacheKey& key, const IntrinsicFaceData<std::array<double, 2>>& values) const {
  static_assert(sizeof(std::array<double, 2>) == 2 * sizeof(double), "vectors are stored as packed pairs");
  return store(key, MapKind::Vector, values.empty() ? nullptr : values[0].data(), values.size());
}

void MapCache::evict_beyond_budget(const fs::path& keep) const {
  struct Entry {
    fs::path path;
    fs::file_time_type used;
    std::uintmax_t bytes;
  };
  std::vector<Entry> entries;
  std::uintmax_t total = 0;
  std::error_code ec;
  for (fs::directory_iterator it(keep.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() != kEntrySuffix || !it->is_regular_file(ec)) continue;
    const std::uintmax_t bytes = it->file_size(ec);
    const fs::file_time_type used = it->last_write_time(ec);
    if (ec) continue;  // removed meanwhile by another process
    entries.push_back({it->path(), used, bytes});
    total += bytes;
  }
  if (total <= max_bytes_) return;
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
  for (const Entry& e : entries) {
    if (total <= max_bytes_) break;
    if (e.path == keep) continue;
    if (fs::remove(e.path, ec)) total -= e.bytes;
  }
}

}  // namespace physarum
