// The reaction-diffusion keys of a scene (common/scene/scene_reaction_diffusion.hpp): a named model fills
// in its formulas and the papers' defaults, the file overrides them, custom kinetics are parsed, and
// every bad value is refused with the key (and, for a formula, the position) in the message.
#include "common/reaction_diffusion/reaction_formula.hpp"
#include "common/reaction_diffusion/reaction_models.hpp"
#include "reaction_diffusion_scene.hpp"

#include <gtest/gtest.h>

#include <string>

namespace physarum {
namespace {

using nlohmann::json;


json base(json extra) {
  json j = {{"mesh", "shape:square"}, {"time_step", 1.0}};
  for (auto it = extra.begin(); it != extra.end(); ++it) j[it.key()] = it.value();
  return j;
}

// The message of the InputError loading `j` throws ("" when none).
std::string error_of(const json& j) {
  try {
    scene_from_json(j);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

double coefficient(const ReactionDiffusionSpec& spec, const std::string& name) {
  for (const auto& [n, v] : spec.coefficients)
    if (n == name) return std::get<double>(v);
  ADD_FAILURE() << "no coefficient " << name;
  return 0.0;
}

TEST(ReactionDiffusionScene, NamedModelNeedsNoAgentKeysAndTakesThePapersDefaults) {
  const Scene scene = scene_from_json(base({{"model", "gray-scott"}}));
  ASSERT_NE(scene.reaction_diffusion(), nullptr);
  const ReactionDiffusionSpec& rd = *scene.reaction_diffusion();
  ASSERT_EQ(rd.morphogens.size(), 2u);
  EXPECT_EQ(rd.morphogens[0].name, "u");
  EXPECT_EQ(rd.morphogens[1].name, "v");
  // Pearson 1993: F = 0.04, k = 0.06, D_u = 2e-5, D_v = 1e-5, from the trivial state (1, 0).
  EXPECT_EQ(coefficient(rd, "F"), 0.04);
  EXPECT_EQ(coefficient(rd, "k"), 0.06);
  EXPECT_EQ(std::get<double>(rd.morphogens[0].diffusion), 2e-5);
  EXPECT_EQ(std::get<double>(rd.morphogens[1].diffusion), 1e-5);
  EXPECT_EQ(std::get<double>(rd.morphogens[0].initial), 1.0);
  EXPECT_EQ(std::get<double>(rd.morphogens[1].initial), 0.0);
  EXPECT_EQ(rd.preview_morphogen, "v");  // the second by default
  EXPECT_EQ(rd.integrator, Integrator::Forward);
}

TEST(ReactionDiffusionScene, NamedModelFormulasHaveTheirUniformSteadyStates) {
  // Each named model's formulas, evaluated where its equations (written independently here) vanish.
  auto value = [](const std::string& model, int m, std::vector<double> point) {
    const ReactionModel& r = *find_reaction_model(model);
    std::vector<std::string> names = r.morphogens;
    for (const auto& c : r.coefficients) names.push_back(c.first), point.push_back(c.second);
    return ReactionFormula(r.reaction[static_cast<size_t>(m)], names, "test").evaluate(point);
  };
  // Gray-Scott: (1, 0) for any F, k.
  EXPECT_EQ(value("gray-scott", 0, {1.0, 0.0}), 0.0);
  EXPECT_EQ(value("gray-scott", 1, {1.0, 0.0}), 0.0);
  // Turing, alpha = 16, beta = 12: u v = 16, v = 4.
  EXPECT_NEAR(value("turing", 0, {4.0, 4.0}), 0.0, 1e-15);
  EXPECT_NEAR(value("turing", 1, {4.0, 4.0}), 0.0, 1e-15);
  // Gray-Scott at (u, v) = (0.5, 0.25): -u v^2 + F (1 - u) = -0.03125 + 0.02 = -0.01125.
  EXPECT_NEAR(value("gray-scott", 0, {0.5, 0.25}), -0.01125, 1e-15);
  // Activator-substrate at (a, s) = (0, 1): rho_s0 - mu_s = 0 for Fig. 20's values.
  EXPECT_NEAR(value("activator-substrate", 1, {0.0, 1.0}), 0.0, 1e-15);
  // The appendix of 004 with beta at its mean. Turk's spots: a b = 16 and a b - b = 12 give (4, 4).
  EXPECT_NEAR(value("turing-spots", 0, {4.0, 4.0}), 0.0, 1e-15);
  EXPECT_NEAR(value("turing-spots", 1, {4.0, 4.0}), 0.0, 1e-15);
  // Meinhardt's spots, p3 = 0: b p2 = 0.01 a^2 and 0.01 a^2 / b = a p1, so a = p2 / p1 = 4/3 and
  // b = 0.01 (16/9) / 0.04 = 4/9.
  EXPECT_NEAR(value("meinhardt-spots", 0, {4.0 / 3.0, 4.0 / 9.0}), 0.0, 1e-15);
  EXPECT_NEAR(value("meinhardt-spots", 1, {4.0 / 3.0, 4.0 / 9.0}), 0.0, 1e-15);
  // Meinhardt's stripes: d = a, e = b, a + b = k_c / k_ab = 1.5 and c = 0.01 a b / k_ab; on the
  // family, not only at its symmetric point (a, b) = (0.75, 0.75).
  for (const double a : {0.75, 0.5, 1.2}) {
    const double b = 1.5 - a, c = 0.01 * a * b / 0.04;
    for (int m = 0; m < 5; ++m) EXPECT_NEAR(value("meinhardt-stripes", m, {a, b, c, a, b}), 0.0, 1e-15) << a << " " << m;
  }
  // ... and off it the stripe system moves: a above its partner's level is driven further up.
  EXPECT_GT(value("meinhardt-stripes", 0, {0.8, 0.75, 0.140625, 0.75, 0.75}), 0.0);
}

TEST(ReactionDiffusionScene, TheAppendixModelsCarryTheirBetaNoiseUnlessTheSceneSetsIt) {
  const Scene stripes = scene_from_json(base({{"model", "meinhardt-stripes"}}));
  ASSERT_EQ(stripes.reaction_diffusion()->parameter_noise.size(), 1u);
  EXPECT_EQ(stripes.reaction_diffusion()->parameter_noise[0], (std::pair<std::string, double>{"beta", 0.1}));
  EXPECT_EQ(stripes.reaction_diffusion()->morphogens.size(), 5u);
  const Scene quiet = scene_from_json(base({{"model", "turing-spots"}, {"parameter_noise", {{"beta", 0.0}}}}));
  EXPECT_EQ(quiet.reaction_diffusion()->parameter_noise[0].second, 0.0);
  // A model without a default noise takes one for any of its coefficients.
  const Scene gray = scene_from_json(base({{"model", "gray-scott"}, {"parameter_noise", {{"k", 0.001}}}}));
  ASSERT_EQ(gray.reaction_diffusion()->parameter_noise.size(), 1u);
  EXPECT_EQ(gray.reaction_diffusion()->parameter_noise[0].first, "k");
}

TEST(ReactionDiffusionScene, FileOverridesTheModelsValues) {
  const Scene scene = scene_from_json(base({{"model", "gray-scott"},
                                          {"parameters", {{"F", 0.03}}},
                                          {"morphogens", {{"v", {{"diffusion", 3e-5}, {"initial", 0.5}}}}},
                                          {"integrator", "imex"},
                                          {"preview_morphogen", "u"}}));
  const ReactionDiffusionSpec& rd = *scene.reaction_diffusion();
  EXPECT_EQ(coefficient(rd, "F"), 0.03);
  EXPECT_EQ(coefficient(rd, "k"), 0.06);
  EXPECT_EQ(std::get<double>(rd.morphogens[1].diffusion), 3e-5);
  EXPECT_EQ(std::get<double>(rd.morphogens[1].initial), 0.5);
  EXPECT_EQ(rd.integrator, Integrator::Imex);
  EXPECT_EQ(rd.preview_morphogen, "u");
}

TEST(ReactionDiffusionScene, CustomKineticsTakeTheMorphogensInAlphabeticalOrder) {
  const Scene scene = scene_from_json(base({{"reaction", {{"w", "-w + a*u"}, {"u", "a - u"}, {"v", "u - v"}}},
                                          {"parameters", {{"a", 2.0}}},
                                          {"morphogens", {{"u", {{"diffusion", 1e-4}}},
                                                          {"v", {{"diffusion", 0.0}}},
                                                          {"w", {{"diffusion", 1e-5}, {"initial", 3.0}}}}}}));
  const ReactionDiffusionSpec& rd = *scene.reaction_diffusion();
  EXPECT_EQ(rd.model, "custom");
  ASSERT_EQ(rd.morphogens.size(), 3u);
  EXPECT_EQ(rd.morphogens[0].name, "u");
  EXPECT_EQ(rd.morphogens[2].name, "w");
  EXPECT_EQ(rd.reaction[2], "-w + a*u");
  EXPECT_EQ(std::get<double>(rd.morphogens[2].initial), 3.0);
}

TEST(ReactionDiffusionScene, AFormulaWithAnUnknownNameIsRefusedWithItsPosition) {
  const std::string e = error_of(base({{"reaction", {{"u", "u*v - q"}, {"v", "u"}}},
                                       {"morphogens", {{"u", {{"diffusion", 1.0}}}, {"v", {{"diffusion", 1.0}}}}}}));
  EXPECT_NE(e.find("reaction.u"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown name 'q' at position 7"), std::string::npos) << e;
  // A function outside the contract's list is an unknown name too.
  const std::string tan = error_of(base({{"reaction", {{"u", "tan(u)"}, {"v", "u"}}},
                                         {"morphogens", {{"u", {{"diffusion", 1.0}}}, {"v", {{"diffusion", 1.0}}}}}}));
  EXPECT_NE(tan.find("unknown name 'tan' at position 1"), std::string::npos) << tan;
  const std::string syntax = error_of(base({{"reaction", {{"u", "u*(v"}, {"v", "u"}}},
                                            {"morphogens", {{"u", {{"diffusion", 1.0}}}, {"v", {{"diffusion", 1.0}}}}}}));
  EXPECT_NE(syntax.find("reaction.u"), std::string::npos) << syntax;
  const std::string comparison = error_of(base({{"reaction", {{"u", "u > v"}, {"v", "u"}}},
                                                {"morphogens", {{"u", {{"diffusion", 1.0}}}, {"v", {{"diffusion", 1.0}}}}}}));
  EXPECT_NE(comparison.find("'>' at position 3"), std::string::npos) << comparison;
}

TEST(ReactionDiffusionScene, BadValuesAreRefusedNamingTheKey) {
  struct Case {
    json scene;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {base({{"model", "gray-scott"}, {"morphogens", {{"u", {{"diffusion", -1e-5}}}}}}), "morphogens.u.diffusion"},
      {base({{"reaction", {{"u", "-u"}}}, {"morphogens", {{"u", {{"diffusion", 1.0}}}}}}), "2 to 8"},
      {base({{"reaction", {{"a", "b"}, {"b", "c"}, {"c", "d"}, {"d", "e"}, {"e", "f"}, {"f", "g"}, {"g", "h"},
                           {"h", "i"}, {"i", "a"}}}}),
       "has 9 morphogens; a system has 2 to 8"},
      {base({{"reaction", {{"u", "-u"}, {"x", "u - x"}}}, {"morphogens", {{"u", {{"diffusion", 1.0}}}, {"x", {{"diffusion", 1.0}}}}}}),
       "key 'reaction.x': 'x' is a vertex property of the PLY files a run writes"},
      {base({{"maps", {{"east", {{"direction", {1, 0, 0}}}}}},
             {"model", "turing"},
             {"morphogens", {{"v", {{"anisotropy", {{"direction", "east"}, {"ratio", 0.0}}}}}}}}),
       "morphogens.v.anisotropy.ratio"},
      {base({{"model", "gray-scott"}, {"parameters", {{"f", 0.04}}}}), "parameters.f"},
      {base({{"model", "gray-scott"}, {"morphogens", {{"w", {{"initial", 1.0}}}}}}), "morphogens.w"},
      {base({{"model", "grey-scott"}}), "'model'"},
      {base({{"model", "gray-scott"}, {"agents", 100}}), "'agents'"},
      {base({{"model", "gray-scott"}, {"integrator", "backward"}}), "imex"},
      {base({{"agents", 10}, {"sensor_distance", 0.05}, {"morphogens", {{"u", {{"diffusion", 1.0}}}}}}), "'morphogens'"},
      {base({{"model", "gray-scott"}, {"parameters", {{"F", "nomap"}}}}), "parameters.F"},
      {base({{"model", "gray-scott"}, {"dirichlet", {{"map", "nomap"}}}}), "dirichlet.map"},
      {base({{"model", "gray-scott"}, {"preview_morphogen", "w"}}), "preview_morphogen"},
      {base({{"model", "gray-scott"}, {"initial", {{"noise", -0.1}}}}), "initial.noise"},
      {base({{"model", "meinhardt-spots"}, {"parameter_noise", {{"gamma", 0.1}}}}),
       "key 'parameter_noise.gamma': no coefficient of that name (the coefficients: s, p1, p2, p3, beta)"},
      {base({{"model", "meinhardt-spots"}, {"parameter_noise", {{"beta", -0.1}}}}), "parameter_noise.beta"},
      {base({{"model", "meinhardt-spots"}, {"parameter_noise", 0.1}}), "parameter_noise"},
      {base({{"model", "gray-scott"}, {"initial", {{"spots", {{"count", 3}, {"radius", 0.0}, {"values", json::object()}}}}}}),
       "initial.spots.radius"},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(c.scene);
    EXPECT_NE(e.find(c.expected), std::string::npos) << c.scene.dump() << "\n -> " << (e.empty() ? "(accepted)" : e);
  }
}

TEST(ReactionDiffusionScene, APhysarumSceneStillNeedsItsAgents) {
  const std::string e = error_of(base({{"sensor_distance", 0.05}}));
  EXPECT_NE(e.find("required key 'agents' is missing"), std::string::npos) << e;
}

}  // namespace
}  // namespace physarum
