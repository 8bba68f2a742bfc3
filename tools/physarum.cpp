// The `physarum` command-line program: one entry point for users, tests and benchmarks.
// Exit codes (docs/commands.md, "Exit codes"): 0 success, 1 bad input or a failed check, 2 usage error.
#include "common/base/errors.hpp"
#include "tools/commands.hpp"

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

// `physarum --help` lists each command in one line: the first line of its description. The whole
// description stays in the command's own --help.
class OneLineCommandList : public CLI::Formatter {
 public:
  std::string make_subcommand(const CLI::App* sub) const override {
    const std::string& description = sub->get_description();
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_display_name(true), description.substr(0, description.find('\n')),
                             column_width_);
    return out.str();
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"physarum — Physarum slime-mold patterns grown on intrinsic triangulations of curved surfaces"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "physarum 0.1");
  app.formatter(std::make_shared<OneLineCommandList>());
  app.footer("Each command's own --help has the details; docs/commands.md is the manual.\n");

  const std::vector<physarum::cli::Command> commands = physarum::cli::add_all_commands(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  try {
    for (const auto& command : commands)
      if (command.app->parsed()) return command.run();
  } catch (const physarum::UsageError& e) {
    std::cerr << "physarum: usage error: " << e.what() << "\n";
    return 2;
  } catch (const physarum::DeviceError& e) {
    std::cerr << "physarum: device error: " << e.what() << "\n";
    return 1;
  } catch (const physarum::InputError& e) {
    std::cerr << "physarum: error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "physarum: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "physarum: internal error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
