#pragma once
// 64-bit content hashes for cache keys (common/maps/map_cache.hpp): xxHash's XXH3 (libxxhash), fast enough
// to hash a mesh file or a million-face triangulation in milliseconds. A cache key, not a security
// measure: a collision is not defended against here, which is why a cache entry also stores the
// full text of its key and is used only when that text matches.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace physarum {

// Feeds bytes into one XXH3-64 digest, in pieces.
class ContentHasher {
 public:
  ContentHasher();
  ~ContentHasher();
  ContentHasher(const ContentHasher&) = delete;
  ContentHasher& operator=(const ContentHasher&) = delete;

  void add_bytes(const void* data, std::size_t size);
  void add(std::string_view text) { add_bytes(text.data(), text.size()); }
  // The array's bytes as they lie in memory: only for element types without padding.
  template <class T>
  void add_array(std::span<const T> values) {
    add_bytes(values.data(), values.size_bytes());
  }
  std::uint64_t digest() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

std::uint64_t content_hash(std::string_view bytes);

// The hash of a file's bytes, read in chunks (a large mesh is never held in memory twice).
// InputError naming the file when it cannot be read.
std::uint64_t file_content_hash(const std::string& path);

// The hash of the running program's own executable (/proc/self/exe), computed once: a cache keyed
// with it never serves values computed by another build. 0 when it cannot be read (then entries of
// unreadable builds share the key; the stored key text still has to match).
std::uint64_t executable_hash();

// 16 lower-case hexadecimal digits.
std::string hex64(std::uint64_t value);

}  // namespace physarum
