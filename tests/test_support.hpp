#pragma once
// Helpers shared by the test suites: locating the shared test meshes (skipping cleanly when the
// folder is absent) and running the `physarum` program as a user would.
#include "common/base/errors.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace physarum::testing {

// Absolute path of ../shared/meshes/NAME, or "" when it is not there.
inline std::string shared_mesh_path(const std::string& name) {
  const std::filesystem::path p = std::filesystem::path(PHYSARUM_SHARED_MESHES) / name;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

// Use at the top of a test: binds `var` to the mesh path or skips the test with a clear message.
#define PHYSARUM_REQUIRE_SHARED_MESH(var, name)                                                  \
  const std::string var = ::physarum::testing::shared_mesh_path(name);                           \
  if (var.empty()) GTEST_SKIP() << "shared test mesh " << (name) << " not found under "           \
                                << PHYSARUM_SHARED_MESHES << " (the shared/ folder is absent)"

struct CommandResult {
  int exit_code = -1;
  std::string out;  // standard output
  std::string err;  // standard error
};

// Runs a shell command line and captures both streams and the exit code (-1 when it did not exit).
inline CommandResult run_command(const std::string& command) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("physarum_cmd_" + std::to_string(::getpid()) + "_" +
                                     std::to_string(reinterpret_cast<uintptr_t>(&command)));
  std::filesystem::create_directories(dir);
  const std::string out_file = (dir / "out").string(), err_file = (dir / "err").string();
  const std::string cmd = "{ " + command + "\n} >'" + out_file + "' 2>'" + err_file + "'";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  auto slurp = [](const std::string& path) {
    std::string s;
    if (FILE* f = std::fopen(path.c_str(), "rb")) {
      std::array<char, 4096> buf;
      size_t n;
      while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) s.append(buf.data(), n);
      std::fclose(f);
    }
    return s;
  };
  r.out = slurp(out_file);
  r.err = slurp(err_file);
  std::filesystem::remove_all(dir);
  return r;
}

// Runs `physarum ARGS` through the shell (ARGS is shell-quoted by the caller).
inline CommandResult run_physarum(const std::string& args) {
  return run_command(std::string("'") + PHYSARUM_EXE + "' " + args);
}

// A shell command's exit code (-1 when it did not exit), its output left where the command sends it.
inline int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A path single-quoted for run_physarum's shell command line (paths with spaces stay one argument).
inline std::string quoted(const std::filesystem::path& p) {
  std::string q(1, '\'');  // built by appending: "'" + s trips a GCC 12 -Wrestrict false positive
  q += p.string();
  q += '\'';
  return q;
}

// A fresh empty temporary directory, removed when the object goes out of scope.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    static int counter = 0;
    path = std::filesystem::temp_directory_path() /
           ("physarum_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

// The message of the InputError `f` throws ("" when it does not throw).
template <class F>
std::string input_error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

}  // namespace physarum::testing
