#include "common/scene/scene_fields.hpp"

#include "common/base/errors.hpp"

#include <algorithm>

namespace physarum {

std::string scene_where(const std::string& source) { return source.empty() ? std::string("scene") : source; }

void fail_key(const std::string& source, std::string_view key, const std::string& problem) {
  throw InputError(scene_where(source) + ": key '" + std::string(key) + "': " + problem);
}

void only_fields(const nlohmann::json& entry, std::initializer_list<const char*> allowed, const std::string& source,
                 std::string_view key) {
  if (!entry.is_object()) fail_key(source, key, entry.dump() + " must be an object");
  for (auto it = entry.begin(); it != entry.end(); ++it)
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return it.key() == a; })) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "\"" : ", \"") + std::string(a) + "\"";
      fail_key(source, key, "unknown field \"" + it.key() + "\" (it takes " + list + ")");
    }
}

}  // namespace physarum
