// Every scene shipped in tools/scenes/ runs from a fresh clone: the files git tracks (and new ones
// it does not ignore: what the next commit holds) are copied into an empty folder with nothing
// beside it (no ../shared, no build/, no out/), and `physarum run` takes each scene there for two
// steps (a growth scene: two reaction steps and one growth step). A scene that names a file outside the repository, a mesh that is not shipped, or a key
// the program no longer reads fails here with the program's own message. cascade_second.json reads
// what cascade_first.json wrote to out/cascade_first (tools/scenes/README.md), so that one runs first.
#include "test_support.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;

// The repository's files as a clone would have them ("" entries dropped), or empty when git cannot
// list them (a source tree without its .git).
std::vector<std::string> files_of_a_clone() {
  const CommandResult listed = run_command("git -C " + quoted(PHYSARUM_SOURCE_DIR) +
                                           " ls-files --cached --others --exclude-standard");
  std::vector<std::string> files;
  if (listed.exit_code != 0) return files;
  std::istringstream in(listed.out);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && fs::is_regular_file(fs::path(PHYSARUM_SOURCE_DIR) / line)) files.push_back(line);
  return files;
}

// The scenes among them: tools/scenes/**/*.json, cascade_first before cascade_second.
std::vector<std::string> shipped_scenes(const std::vector<std::string>& files) {
  std::vector<std::string> scenes;
  for (const std::string& f : files)
    if (f.rfind("tools/scenes/", 0) == 0 && fs::path(f).extension() == ".json") scenes.push_back(f);
  std::sort(scenes.begin(), scenes.end());
  std::stable_partition(scenes.begin(), scenes.end(),
                        [](const std::string& s) { return s.find("cascade_first") != std::string::npos; });
  return scenes;
}

TEST(ShippedScenes, EveryOneRunsFromAFreshClone) {
  const std::vector<std::string> files = files_of_a_clone();
  if (files.empty()) GTEST_SKIP() << "git cannot list the files of " << PHYSARUM_SOURCE_DIR << " (no .git): no clone to make";
  const std::vector<std::string> scenes = shipped_scenes(files);
  ASSERT_GE(scenes.size(), 40u) << "tools/scenes/ should hold the shipped scenes";

  TempDir dir;
  const fs::path clone = dir.path / "clone";
  for (const std::string& f : files) {
    fs::create_directories((clone / f).parent_path());
    fs::copy_file(fs::path(PHYSARUM_SOURCE_DIR) / f, clone / f);
  }
  ASSERT_FALSE(fs::exists(dir.path / "shared")) << "the clone must have nothing beside it";

  for (const std::string& scene : scenes) {
    // Two steps. A growth scene's length is its schedule: two reaction steps and one growth step,
    // and a prescribed stretch set to none (a whole stretch in one Newton solve need not converge).
    std::ifstream file(fs::path(PHYSARUM_SOURCE_DIR) / scene);
    const std::string text(std::istreambuf_iterator<char>(file), {});
    std::string length = " --steps 2";
    if (text.find("\"schedule\"") != std::string::npos)
      length = " --set schedule.reaction_steps=2 --set schedule.growth_steps=1";
    if (text.find("\"stretch\"") != std::string::npos) length += " --set growth.stretch=1";
    const bool first_of_cascade = scene.find("cascade_first") != std::string::npos;
    const std::string out = first_of_cascade ? "out/cascade_first" : (dir.path / "runs" / scene).string();
    // From the clone's top, as the README's commands run; a small texture keeps the bakes quick.
    const CommandResult r = run_command("cd " + quoted(clone) + " && '" + PHYSARUM_EXE + "' run " + quoted(fs::path(scene)) +
                                        length + " --texture-size 64 --out " + quoted(fs::path(out)));
    EXPECT_EQ(r.exit_code, 0) << scene << " does not run from a fresh clone:\n" << r.err;
    // (out is relative to the clone for cascade_first, absolute otherwise: operator/ keeps an absolute one.)
    EXPECT_TRUE(fs::exists(clone / out / "run.json"))
        << scene << ": no run.json written\n" << r.err;
  }
}

}  // namespace
}  // namespace physarum::testing
