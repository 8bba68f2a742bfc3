#pragma once
// The map cache's environment (PHYSARUM_CACHE_DIR, PHYSARUM_NO_CACHE) set for one test and restored
// after it: the commands a test starts inherit it, so a test can watch a second run read the cache
// without touching the user's own cache folder.
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace physarum::testing {

class CacheEnvironment {
 public:
  explicit CacheEnvironment(const std::filesystem::path& folder, bool off = false) {
    save("PHYSARUM_CACHE_DIR");
    save("PHYSARUM_NO_CACHE");
    ::setenv("PHYSARUM_CACHE_DIR", folder.c_str(), 1);
    if (off) ::setenv("PHYSARUM_NO_CACHE", "1", 1);
    else ::unsetenv("PHYSARUM_NO_CACHE");
  }
  ~CacheEnvironment() {
    for (const auto& [name, value] : saved_)
      if (value) ::setenv(name.c_str(), value->c_str(), 1);
      else ::unsetenv(name.c_str());
  }

 private:
  void save(const std::string& name) {
    const char* v = std::getenv(name.c_str());
    saved_.emplace_back(name, v ? std::optional<std::string>(v) : std::nullopt);
  }
  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

}  // namespace physarum::testing
