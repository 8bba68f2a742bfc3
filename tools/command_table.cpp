#include "common/base/errors.hpp"
#include "tools/commands.hpp"

namespace physarum::cli {

std::vector<Command> add_all_commands(CLI::App& parent) {
  std::vector<Command> commands;
  commands.push_back(add_mesh_command(parent));
  commands.push_back(add_devices_command(parent));
  commands.push_back(add_run_command(parent));
  commands.push_back(add_compare_command(parent));
  commands.push_back(add_bench_command(parent));
  commands.push_back(add_scene_keys_command(parent));
  commands.push_back(add_render_command(parent));
  commands.push_back(add_color_map_command(parent));
  commands.push_back(add_map_command(parent));
  commands.push_back(add_analyze_command(parent));
  commands.push_back(add_sweep_command(parent));
  commands.push_back(add_sketch_command(parent));
  return commands;
}

int run_command_line(const std::vector<std::string>& args) {
  CLI::App app{"physarum"};
  app.require_subcommand(1);
  const std::vector<Command> commands = add_all_commands(app);
  // CLI11 takes the words last first.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::Success& e) {  // --help
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
  for (const Command& command : commands)
    if (command.app->parsed()) return command.run();
  throw UsageError("no command given");
}

}  // namespace physarum::cli
