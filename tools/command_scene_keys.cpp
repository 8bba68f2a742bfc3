// `physarum scene-keys`: every key a scene file may contain, with its unit, allowed values, default
// and meaning, as the Markdown table the README shows (common/scene/scene_keys.hpp; the README's copy is
// checked against this by tests/test_parameter_table.cpp).
#include "common/scene/scene_keys.hpp"
#include "tools/commands.hpp"

#include <cstdio>

namespace physarum::cli {

Command add_scene_keys_command(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand(
      "scene-keys", "Print every scene-file key (unit, allowed values, default, meaning) as a Markdown table");
  return {app, [] {
            std::fputs(scene_keys_markdown().c_str(), stdout);
            return 0;
          }};
}

}  // namespace physarum::cli
