// The layering rule, enforced: every folder of common/ is one layer (one library, CMakeLists.txt)
// and includes only from itself and the layers below it; the backends (reference/, opencl/,
// kernels/) see the model and geometry layers only — never a scene file, a map definition, an
// output format or the harness. A violation names the file, the line and the layer it reached.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// Each layer and the layers it builds on directly (the closure is allowed). The order of this table
// is the order of CMakeLists.txt's physarum_layer calls.
const std::map<std::string, std::vector<std::string>> kLayerBelow = {
    {"base", {}},
    {"mesh", {"base"}},
    {"intrinsic", {"mesh"}},
    {"numerics", {"base"}},
    {"surface", {"intrinsic", "numerics"}},
    {"model", {"surface"}},
    {"reaction_diffusion", {"numerics"}},
    {"simulation", {"model", "reaction_diffusion"}},
    {"map_tools", {"surface"}},
    {"maps", {"map_tools"}},
    {"color", {"mesh"}},
    {"shell", {"numerics"}},
    {"growth", {"shell"}},
    {"scene", {"maps", "model", "reaction_diffusion", "color", "growth"}},
    {"setup", {"scene", "simulation"}},
    {"run", {"simulation"}},
    {"harness", {"setup"}},
    {"pattern", {"map_tools"}},
    {"sketch", {"map_tools"}},
    {"output", {"color", "maps"}},
};
// What the backends may include of common/: the simulation interface and everything below it.
const std::vector<std::string> kBackendLayers = {"simulation"};

std::set<std::string> closure(const std::vector<std::string>& roots) {
  std::set<std::string> seen;
  std::vector<std::string> todo = roots;
  while (!todo.empty()) {
    const std::string layer = todo.back();
    todo.pop_back();
    if (!seen.insert(layer).second) continue;
    for (const std::string& below : kLayerBelow.at(layer)) todo.push_back(below);
  }
  return seen;
}

struct Violation {
  std::string where;  // file:line
  std::string layer;  // the layer it included from
};

// Every `#include "common/LAYER/..."` of the files under `folder` whose LAYER is not in `allowed`.
std::vector<Violation> includes_outside(const fs::path& folder, const std::set<std::string>& allowed) {
  static const std::regex include(R"re(^\s*#\s*include\s*"common/([a-z_]+)/)re");
  std::vector<Violation> found;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path());
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      std::smatch m;
      if (std::regex_search(line, m, include) && !allowed.count(m[1].str()))
        found.push_back({fs::relative(e.path(), PHYSARUM_SOURCE_DIR).string() + ":" + std::to_string(n), m[1].str()});
    }
  }
  return found;
}

std::string describe(const std::vector<Violation>& violations) {
  std::string s;
  for (const Violation& v : violations) s += "\n  " + v.where + " includes from common/" + v.layer + "/";
  return s;
}

const fs::path kSource = PHYSARUM_SOURCE_DIR;

TEST(Layering, EveryFolderOfCommonIsALayerOfTheTable) {
  for (const fs::directory_entry& e : fs::directory_iterator(kSource / "common")) {
    if (e.is_directory()) {
      EXPECT_TRUE(kLayerBelow.count(e.path().filename().string()))
          << "common/" << e.path().filename().string() << "/ is not in the layer table of tests/test_layering.cpp";
    } else {
      ADD_FAILURE() << e.path() << " lies directly in common/: put it in the folder of its concept";
    }
  }
}

TEST(Layering, EachLayerIncludesOnlyItselfAndTheLayersBelowIt) {
  for (const auto& [layer, below] : kLayerBelow) {
    std::set<std::string> allowed = closure(below);
    allowed.insert(layer);
    const std::vector<Violation> v = includes_outside(kSource / "common" / layer, allowed);
    EXPECT_TRUE(v.empty()) << "common/" << layer << "/ reaches above its layer:" << describe(v);
  }
}

TEST(Layering, BackendsSeeOnlyTheModelAndGeometryLayers) {
  const std::set<std::string> allowed = closure(kBackendLayers);
  for (const char* backend : {"reference", "opencl", "kernels"}) {
    const std::vector<Violation> v = includes_outside(kSource / backend, allowed);
    EXPECT_TRUE(v.empty()) << backend << "/ includes a header no backend may see (scene, maps, setup, output, "
                           << "harness, ...):" << describe(v);
  }
}

// Every line of the files under `folder` that matches `pattern`, as "file:line: text".
std::vector<std::string> lines_matching(const fs::path& folder, const std::regex& pattern) {
  std::vector<std::string> found;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path());
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
      if (std::regex_search(line, pattern))
        found.push_back(fs::relative(e.path(), kSource).string() + ":" + std::to_string(n) + ": " + line);
  }
  return found;
}

// The command line is a client of the library (api/physarum.hpp): neither the library nor anything
// below it includes a header of tools/.
TEST(Layering, TheLibraryNeverIncludesTheCommandLine) {
  static const std::regex include(R"re(^\s*#\s*include\s*"tools/)re");
  for (const char* folder : {"api", "common", "reference", "opencl"})
    for (const std::string& line : lines_matching(kSource / folder, include)) ADD_FAILURE() << line << " includes the command line";
}

// The Python module binds the library (api/), not the command line: its C++ includes nothing of
// tools/ outside its own folder.
TEST(Layering, ThePythonModuleBindsTheLibraryNotTheCommandLine) {
  static const std::regex include(R"re(^\s*#\s*include\s*"tools/(?!python/))re");
  for (const std::string& line : lines_matching(kSource / "tools" / "python", include))
    ADD_FAILURE() << line << " includes the command line";
}

}  // namespace
