// `physarum mesh` as a user runs it: the JSON contract the README documents, the exit codes, and that the
// refinement flags do what they say.
#include "test_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace physarum {
namespace {

using testing::run_physarum;

nlohmann::json parse_json(const testing::CommandResult& r) {
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(CliMesh, JsonHasTheDocumentedKeys) {
  const auto j = parse_json(run_physarum("mesh shape:sphere --eigenvalues 4 --json"));
  for (const char* k : {"vertices", "faces", "components", "genus", "boundary_loops", "area"})
    EXPECT_TRUE(j["input"].contains(k)) << k;
  for (const char* k : {"vertices", "faces", "delaunay", "min_angle_deg", "max_circumradius", "flips", "insertions", "seconds"})
    EXPECT_TRUE(j["intrinsic"].contains(k)) << k;
  ASSERT_EQ(j["eigenvalues"].size(), 4u);
  // Topology of an icosphere: V - E + F = 2, genus 0, no boundary; a unit sphere has area 4 pi.
  EXPECT_EQ(j["input"]["genus"], 0);
  EXPECT_EQ(j["input"]["boundary_loops"], 0);
  EXPECT_EQ(j["input"]["components"], 1);
  const int v = j["input"]["vertices"], f = j["input"]["faces"];
  EXPECT_EQ(2 * v - 4, f) << "closed triangle mesh of genus 0: F = 2V - 4";
  EXPECT_NEAR(j["input"]["area"].get<double>(), 4 * std::numbers::pi, 0.02 * 4 * std::numbers::pi);
  // Without refinement flags the intrinsic triangulation is the Delaunay one, with no insertions.
  EXPECT_EQ(j["intrinsic"]["insertions"], 0);
  EXPECT_EQ(j["intrinsic"]["vertices"], v);
  EXPECT_TRUE(j["intrinsic"]["delaunay"].get<bool>());
  // The smallest eigenvalue of a connected closed surface is 0; the next three are l(l+1) = 2 (l = 1).
  EXPECT_NEAR(j["eigenvalues"][0].get<double>(), 0.0, 1e-8);
  for (int i = 1; i < 4; ++i) EXPECT_NEAR(j["eigenvalues"][i].get<double>(), 2.0, 0.02);
}

TEST(CliMesh, RefinementRespectsTheRadiusBound) {
  const auto j = parse_json(run_physarum("mesh shape:torus --max-circumradius 0.05 --json"));
  EXPECT_LE(j["intrinsic"]["max_circumradius"].get<double>(), 0.05 * (1 + 1e-9));
  EXPECT_GT(j["intrinsic"]["insertions"].get<int>(), 0);
  EXPECT_TRUE(j["intrinsic"]["delaunay"].get<bool>());
  EXPECT_EQ(j["input"]["genus"], 1);
  // Relative bound: a fraction of the bounding-box diagonal of the torus (R = 1, r = 0.4:
  // box 2.8 x 2.8 x 0.8, diagonal sqrt(2 * 2.8^2 + 0.8^2)).
  const double diagonal = std::sqrt(2 * 2.8 * 2.8 + 0.8 * 0.8);
  const auto k = parse_json(run_physarum("mesh shape:torus --max-circumradius-rel 0.02 --json"));
  EXPECT_LE(k["intrinsic"]["max_circumradius"].get<double>(), 0.02 * diagonal * (1 + 1e-6));
}

TEST(CliMesh, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run_physarum("mesh shape:sphere --max-circumradius 0.1 --max-circumradius-rel 0.1").exit_code, 2);
  EXPECT_EQ(run_physarum("mesh shape:sphere --no-such-flag").exit_code, 2);
  EXPECT_EQ(run_physarum("mesh").exit_code, 2);
  EXPECT_EQ(run_physarum("mesh shape:sphere --max-circumradius -1").exit_code, 2);
  EXPECT_EQ(run_physarum("").exit_code, 2);
}

TEST(CliMesh, BadInputExitsWithOneAndSaysWhat) {
  const auto r = run_physarum("mesh /nonexistent/folder/bunny.obj --json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/nonexistent/folder/bunny.obj"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << "nothing on stdout when the input is refused: " << r.out;
  const auto s = run_physarum("mesh shape:no-such-shape");
  EXPECT_EQ(s.exit_code, 1);
  EXPECT_NE(s.err.find("sphere"), std::string::npos) << "the message lists the valid shapes: " << s.err;
}

TEST(CliMesh, HelpListsTheSubcommands) {
  const auto r = run_physarum("--help");
  EXPECT_EQ(r.exit_code, 0);
  // CLI11 lists each subcommand on its own line, indented, followed by its description.
  for (const char* sub : {"mesh", "run", "devices"})
    EXPECT_NE(r.out.find("\n  " + std::string(sub) + " "), std::string::npos) << "subcommand " << sub << " in:\n" << r.out;
}

// `physarum --help` lists each command in one line (its description's first line); the details stay
// in each command's own --help.
TEST(CliMesh, HelpListsEachCommandInOneLine) {
  const auto r = run_physarum("--help");
  EXPECT_EQ(r.exit_code, 0);
  std::istringstream lines(r.out);
  std::string line;
  int commands = 0;
  while (std::getline(lines, line)) {
    EXPECT_LE(line.size(), 160u) << "a line of --help is a paragraph:\n" << line;
    if (line.rfind("  ", 0) == 0 && line.find("  -") != 0) ++commands;
  }
  EXPECT_GE(commands, 11) << r.out;
  EXPECT_EQ(r.out.find("DIR/fields_full.ply"), std::string::npos) << "run's details belong in run --help:\n" << r.out;
  EXPECT_NE(run_physarum("run --help").out.find("DIR/fields_full.ply"), std::string::npos);
}

// `physarum run --help` must be usable without any file outside this repository: it names the five
// outputs, the stats.csv columns, the default scene and the run-length rule, and points nowhere else.
TEST(CliMesh, RunHelpIsSelfContained) {
  const auto r = run_physarum("run --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* text : {"pheromone.ply", "result.glb", "stats.csv", "preview.png", "run.json",
                           "time,mean,U,coverage_0.5U,coverage_1U,coverage_2U", "tools/scenes/default.json",
                           "--steps", "--sim-time", "sim_time", "--backend", "--device", "--seed", "--out"})
    EXPECT_NE(r.out.find(text), std::string::npos) << "'" << text << "' missing from:\n" << r.out;
  EXPECT_EQ(r.out.find("DESIGN.md"), std::string::npos) << "DESIGN.md is not part of this repository:\n" << r.out;
  for (const char* command : {"mesh --help", "devices --help", "--help"})
    EXPECT_EQ(run_physarum(command).out.find("DESIGN.md"), std::string::npos) << command;
}

}  // namespace
}  // namespace physarum
