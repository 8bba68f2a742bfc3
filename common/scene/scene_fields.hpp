#pragma once
// The checks every scene reader makes on a JSON value, with one wording for every message: the
// scene (its file, or "scene" when built in code), the key, and what is wrong.
#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>
#include <string_view>

namespace physarum {

// The scene's name in messages: its file, or "scene" for a scene built in code.
std::string scene_where(const std::string& source);

// InputError "SOURCE: key 'KEY': PROBLEM".
[[noreturn]] void fail_key(const std::string& source, std::string_view key, const std::string& problem);

// InputError unless `entry` is an object whose fields are all among `allowed` (the message lists them).
void only_fields(const nlohmann::json& entry, std::initializer_list<const char*> allowed, const std::string& source,
                 std::string_view key);

}  // namespace physarum
