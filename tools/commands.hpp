#pragma once
// Each subcommand of the `physarum` program lives in its own file and registers itself here.
// A registered command parses into its own options and returns its exit code when run.
#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace physarum::cli {

struct Command {
  CLI::App* app = nullptr;     // the subcommand, to test whether it was chosen
  std::function<int()> run;    // runs it; returns the exit code
};

Command add_mesh_command(CLI::App& parent);
Command add_devices_command(CLI::App& parent);
Command add_run_command(CLI::App& parent);
Command add_compare_command(CLI::App& parent);
Command add_bench_command(CLI::App& parent);
Command add_scene_keys_command(CLI::App& parent);
Command add_render_command(CLI::App& parent);
Command add_color_map_command(CLI::App& parent);
Command add_map_command(CLI::App& parent);
Command add_analyze_command(CLI::App& parent);
Command add_sweep_command(CLI::App& parent);
Command add_sketch_command(CLI::App& parent);

// Every command above, in the order `physarum --help` lists them (tools/command_table.cpp).
std::vector<Command> add_all_commands(CLI::App& parent);

// `args` (the words after `physarum`) parsed and run in this process as the program runs them, for
// the Python module: returns the exit code; a malformed command line throws UsageError with CLI11's
// message, and the command's own exceptions (InputError, DeviceError, ...) pass through. --help
// prints the help and returns 0.
int run_command_line(const std::vector<std::string>& args);

}  // namespace physarum::cli
