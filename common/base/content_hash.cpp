#include "common/base/content_hash.hpp"

#include "common/base/errors.hpp"

#include <xxhash.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace physarum {

struct ContentHasher::State {
  XXH3_state_t* xxh = nullptr;
};

ContentHasher::ContentHasher() : state_(std::make_unique<State>()) {
  state_->xxh = XXH3_createState();
  if (state_->xxh == nullptr || XXH3_64bits_reset(state_->xxh) != XXH_OK)
    throw std::runtime_error("ContentHasher: cannot create an XXH3 state (out of memory)");
}

ContentHasher::~ContentHasher() { XXH3_freeState(state_->xxh); }

void ContentHasher::add_bytes(const void* data, std::size_t size) {
  if (size > 0) XXH3_64bits_update(state_->xxh, data, size);
}

std::uint64_t ContentHasher::digest() const { return XXH3_64bits_digest(state_->xxh); }

std::uint64_t content_hash(std::string_view bytes) { return XXH3_64bits(bytes.data(), bytes.size()); }

std::uint64_t file_content_hash(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) throw InputError(path + ": cannot read the file to hash it: " + std::strerror(errno));
  ContentHasher hasher;
  std::array<char, 1 << 16> buffer;
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), file)) > 0) hasher.add_bytes(buffer.data(), n);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) throw InputError(path + ": read error while hashing the file");
  return hasher.digest();
}

std::uint64_t executable_hash() {
  static const std::uint64_t hash = [] {
    try {
      return file_content_hash("/proc/self/exe");
    } catch (const InputError&) {
      return std::uint64_t{0};
    }
  }();
  return hash;
}

std::string hex64(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace physarum
