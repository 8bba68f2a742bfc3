// A reaction term that is not finite at the initial state (common/reaction_diffusion/reaction_at_start.hpp)
// is refused before the run, naming the formula and the values it was evaluated at, instead of
// running and being reported as diverged: u/0 (infinite), log(-1) and sqrt(-u) with u > 0 (NaN), by
// the check itself and through `physarum run`, which writes nothing. A vertex held by a Dirichlet
// region never takes R, so a formula that is only infinite there is accepted, as is a finite one.
#include "common/base/errors.hpp"
#include "common/reaction_diffusion/reaction_at_start.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;

// Three vertices with u = 1, 2, 3 and v = 0, and a coefficient F = 0.5.
ReactionDiffusionSystem three_vertices(const std::string& reaction_u) {
  ReactionDiffusionSystem s;
  s.morphogens = {"u", "v"};
  s.reaction = {reaction_u, "0"};
  s.coefficient_names = {"F"};
  s.coefficients = {IntrinsicVertexData<double>({0.5, 0.5, 0.5})};
  s.initial = {IntrinsicVertexData<double>({1.0, 2.0, 3.0}), IntrinsicVertexData<double>({0.0, 0.0, 0.0})};
  s.mass = IntrinsicVertexData<double>({1.0, 1.0, 1.0});
  return s;
}

std::string refusal(const ReactionDiffusionSystem& s) {
  try {
    check_reactions_finite_at_start(s, {"scene.json: key 'reaction.u'", "scene.json: key 'reaction.v'"});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReactionAtStart, AFormulaNotFiniteAtTheInitialStateIsRefusedNamingItAndTheValues) {
  EXPECT_EQ(refusal(three_vertices("u/0")),
            "scene.json: key 'reaction.u': \"u/0\" is +infinity at the initial state (intrinsic vertex 0: u = 1, "
            "v = 0, F = 0.5), so the run could not take a single step; change the formula, or the initial values or "
            "coefficients it is evaluated at");
  EXPECT_NE(refusal(three_vertices("F*log(-1)")).find("\"F*log(-1)\" is NaN at the initial state (intrinsic vertex 0:"),
            std::string::npos);
  // Finite at u = 1 and 2: the first vertex where it is not is named, with its values.
  EXPECT_NE(refusal(three_vertices("1/(u-3)")).find("is +infinity at the initial state (intrinsic vertex 2: u = 3, v = 0"),
            std::string::npos)
      << refusal(three_vertices("1/(u-3)"));
  EXPECT_EQ(refusal(three_vertices("-u*v^2 + F*(1-u)")), "");
}

TEST(ReactionAtStart, AHeldVertexNeverTakesTheReactionSoItIsNotChecked) {
  ReactionDiffusionSystem s = three_vertices("1/(u-3)");
  s.fixed = {0, 0, 1};
  EXPECT_EQ(refusal(s), "");
  s.fixed = {0, 1, 0};
  EXPECT_NE(refusal(s), "");
}

TEST(ReactionAtStart, ARunOfSuchAFormulaIsRefusedBeforeItWritesAnything) {
  TempDir dir;
  const nlohmann::json scene = {
      {"mesh", "shape:square"}, {"scale_to_area", 0.04}, {"max_circumradius", 0.02}, {"time_step", 0.1},
      {"reaction", {{"u", "sqrt(-u) - v"}, {"v", "u - v"}}},
      {"morphogens", {{"u", {{"diffusion", 1e-5}, {"initial", 0.5}}}, {"v", {{"diffusion", 1e-5}, {"initial", 0.0}}}}}};
  std::ofstream(dir.path / "scene.json") << scene.dump();
  const CommandResult r =
      run_physarum("run " + quoted(dir.path / "scene.json") + " --steps 5 --backend reference --out " + quoted(dir.path / "out"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("key 'reaction.u': \"sqrt(-u) - v\" is NaN at the initial state (intrinsic vertex 0: u = 0.5, v = 0)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("diverged"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "out" / "run.json"));
}

}  // namespace
}  // namespace physarum::testing
