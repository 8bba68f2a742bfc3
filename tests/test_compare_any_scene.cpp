// The differential harness on scenes nobody tuned it for: shipped scenes with no compare_* keys,
// run at the default settings (metrics from the scene's own scales, sequential seeds up to the
// default budget), must be judged equivalent; the same machinery between two arms of one scene
// (--arm) decides the paper's resolution claims; and the number of worker threads does not change
// a verdict.
//
// In CI: the new scenes' equivalence verdicts, the --jobs check and the usage errors.
// Labelled `validation` (ctest -L validation; suites named Validation*): the planted faults on the
// new scenes and the resolution and time-step studies, which take ~15 minutes here.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <ostream>
#include <string>
#include <vector>

namespace physarum::testing {
namespace {

std::string scene_path(const std::string& name) { return std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/" + name + ".json"; }

struct Verdict {
  CommandResult run;
  nlohmann::json json;
};

Verdict compare(const std::string& scene, const std::string& extra) {
  Verdict v;
  v.run = run_physarum("compare '" + scene_path(scene) + "' " + extra);
  try {
    v.json = nlohmann::json::parse(v.run.out);
  } catch (const nlohmann::json::exception&) {
    v.json = nlohmann::json();
  }
  return v;
}

std::string summary(const Verdict& v) {
  // Built by appending: "text" + string trips a GCC 12 -Wrestrict false positive.
  std::string s;
  if (!v.json.is_object()) return s.append("no verdict: ").append(v.run.err);
  s.append(v.json["verdict"].get<std::string>()).append(" after ").append(v.json["seeds"].dump()).append(" seeds;");
  for (const auto& m : v.json["metrics"])
    if (m["verdict"] != "equivalent")
      s.append(" ").append(m["name"].get<std::string>()).append(" (").append(m["verdict"].get<std::string>()).append(")");
  return s;
}

// ---- new scenes at default settings: equivalent ----

class NewScene : public ::testing::TestWithParam<std::string> {};

TEST_P(NewScene, IsJudgedEquivalentAtDefaultSettings) {
  const Verdict v = compare(GetParam(), "");
  ASSERT_TRUE(v.json.is_object()) << v.run.err;
  std::cout << GetParam() << ": " << summary(v) << ", " << v.json["run"]["seconds"] << " s\n";
  EXPECT_EQ(v.run.exit_code, 0) << summary(v);
  EXPECT_EQ(v.json["verdict"], "equivalent");
  for (const char* key : {"arms", "seeds", "sequential", "left_out", "metrics"}) EXPECT_TRUE(v.json.contains(key)) << key;
}

INSTANTIATE_TEST_SUITE_P(CompareAnyScene, NewScene, ::testing::Values("default", "repulsion", "torus_backward", "horn", "saddle"),
                         [](const auto& param_info) { return param_info.param; });

// A real mesh a user might bring: many components and open boundaries, unequal faces, long steps.
TEST(CompareAnyScene, TeapotIsJudgedEquivalentAtDefaultSettings) {
  PHYSARUM_REQUIRE_SHARED_MESH(mesh, "teapot.obj");
  const Verdict v = compare("teapot", "");
  ASSERT_TRUE(v.json.is_object()) << v.run.err;
  std::cout << "teapot: " << summary(v) << ", " << v.json["run"]["seconds"] << " s\n";
  EXPECT_EQ(v.json["verdict"], "equivalent");
}

// The default scene's 48 eigenpairs reach wavelengths far above its pattern (sensor distance 5 cm):
// the harmonic bands are left out, and the verdict says why. With --out, the folder gets the verdict
// and no spectra.png (nothing to draw), and the verdict's exit code stands: a picture with nothing
// to show never turns a verdict into bad input (exit 1).
TEST(CompareAnyScene, SpectralBandsAboveThePatternAreLeftOutWithAReason) {
  TempDir out;
  const Verdict v = compare("default", "--max-seeds 8 --out " + quoted(out.path));
  ASSERT_TRUE(v.json.is_object()) << v.run.err;
  EXPECT_NE(v.run.exit_code, 1) << v.run.err;
  EXPECT_TRUE(std::filesystem::exists(out.path / "verdict.json"));
  EXPECT_TRUE(std::filesystem::exists(out.path / "seed_metrics.csv"));
  EXPECT_FALSE(std::filesystem::exists(out.path / "spectra.png"));
  EXPECT_NE(v.run.err.find("spectra.png not written"), std::string::npos) << v.run.err;
  bool harmonic = false;
  for (const auto& m : v.json["metrics"]) harmonic = harmonic || m["name"].get<std::string>().rfind("harmonic", 0) == 0;
  EXPECT_FALSE(harmonic);
  ASSERT_EQ(v.json["left_out"].size(), 1u);
  EXPECT_NE(v.json["left_out"][0].get<std::string>().find("compare_eigenpairs"), std::string::npos);
}

// ---- each arm against theory, apart from the arms against each other ----

// Long steps (k dt = 0.1) and a diffusion fast enough for several forward-Euler sub-steps: both
// backends settle ~4 % above Eq. 5's U, beyond the 3 % margin on mean / U, exactly as the
// time-discrete model does (common/model/discrete_steady_state.hpp). The arms agree with each other
// and with that model: the verdict is equivalent (exit 0), and the theory section reports each arm
// against the discrete model's value, not against 1.
TEST(CompareAnyScene, ArmsAboveUByTheTimeDiscretisationAreJudgedAgainstEachOther) {
  TempDir dir;
  const std::filesystem::path scene = dir.path / "long_steps.json";
  std::ofstream(scene) << R"({"mesh": "shape:sphere", "scale_to_area": 4.0, "max_circumradius": 0.05, "agents": 4000,
    "time_step": 0.04, "sensor_distance": 0.1, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
    "turn_frequency": 10.0, "deposit_rate": 1.0, "decay_rate": 2.5, "diffuse_rate": 0.05, "mean_lifetime": 0.2,
    "activation_time": 0.08, "integrator": "forward", "seed": 3})";
  const CommandResult run = run_physarum("compare " + quoted(scene));
  nlohmann::json v;
  ASSERT_NO_THROW(v = nlohmann::json::parse(run.out)) << run.err;
  EXPECT_EQ(run.exit_code, 0) << run.out;
  EXPECT_EQ(v["verdict"], "equivalent");
  ASSERT_TRUE(v["theory"].is_object()) << v.dump(1);
  ASSERT_EQ(v["theory"]["arms"].size(), 2u);
  for (const auto& arm : v["theory"]["arms"]) {
    EXPECT_GT(arm["expected_mean_over_U"].get<double>(), 1.03) << arm.dump();
    EXPECT_GT(arm["mean_over_U"].get<double>(), 1.03) << arm.dump();
    EXPECT_EQ(arm["verdict"], "equivalent") << arm.dump();
  }
  for (const auto& m : v["metrics"]) EXPECT_NE(m["name"], "mean_over_U_vs_analytic");
  EXPECT_NE(run.err.find("physarum compare: theory:"), std::string::npos) << run.err;
}

// ---- every core: the same verdict with one worker and with two ----

TEST(CompareAnyScene, OneAndTwoJobsGiveTheSameVerdict) {
  const Verdict one = compare("repulsion", "--max-seeds 16 --jobs 1");
  const Verdict two = compare("repulsion", "--max-seeds 16 --jobs 2");
  ASSERT_TRUE(one.json.is_object() && two.json.is_object()) << one.run.err << two.run.err;
  nlohmann::json a = one.json, b = two.json;
  EXPECT_EQ(a["run"]["jobs"], 1);
  EXPECT_EQ(b["run"]["jobs"], 2);
  a.erase("run");  // wall time and thread count: the only parts that may differ
  b.erase("run");
  EXPECT_EQ(a.dump(), b.dump());
  std::cout << "--jobs 1: " << one.json["run"]["seconds"] << " s, --jobs 2: " << two.json["run"]["seconds"] << " s\n";
}

TEST(CompareAnyScene, ArmsAreCheckedBeforeAnythingRuns) {
  EXPECT_EQ(compare("repulsion", "--arm agents=100").run.exit_code, 2);
  EXPECT_EQ(compare("repulsion", "--arm agents=100 --arm backend=cuda").run.exit_code, 2);
  EXPECT_EQ(compare("repulsion", "--arm agents=100 --arm agents=100").run.exit_code, 2);
  const Verdict unknown = compare("repulsion", "--arm agnets=100 --arm agents=200");
  EXPECT_EQ(unknown.run.exit_code, 1);
  EXPECT_NE(unknown.run.err.find("agnets"), std::string::npos) << unknown.run.err;
  EXPECT_EQ(compare("repulsion", "--arm agents=100 --arm agents=200 --reference-stats x.json").run.exit_code, 2);
}

// ---- validation: planted faults on the new scenes ----

// Each scene's faults in four groups: those that change its model by more than its margins (the
// harness must call them different), those that cannot change it at all (it must not call them
// different: a false alarm), those whose real effect is near the margins (it must not call them
// equivalent), and those whose effect there is near or below the margins, which are only reported.
// The groups follow from the scenes' settings, as the comments say.
struct FaultsOnScene {
  std::string scene;
  std::vector<std::string> different, no_op, reported;
  std::string shared_mesh = "";  // the scene's mesh under ../shared/meshes, when it has one
  std::vector<std::string> not_equivalent = {};
};

void PrintTo(const FaultsOnScene& c, std::ostream* os) { *os << c.scene; }

class ValidationFaultsOnNewScene : public ::testing::TestWithParam<FaultsOnScene> {};

TEST_P(ValidationFaultsOnNewScene, FaultsThatChangeTheModelAreDifferentAndNoOpsAreNot) {
  const FaultsOnScene& c = GetParam();
  if (!c.shared_mesh.empty()) {
    PHYSARUM_REQUIRE_SHARED_MESH(mesh, c.shared_mesh);
  }
  auto run = [&](const std::string& fault) {
    const Verdict v = compare(c.scene, "--fault " + fault);
    EXPECT_TRUE(v.json.is_object()) << fault << ": " << v.run.err;
    std::cout << c.scene << " with " << fault << ": " << summary(v) << "\n";
    return v.json.is_object() ? v.json["verdict"].get<std::string>() : std::string("none");
  };
  for (const std::string& fault : c.different) EXPECT_EQ(run(fault), "different") << fault << " on " << c.scene;
  for (const std::string& fault : c.no_op) EXPECT_NE(run(fault), "different") << fault << " on " << c.scene;
  for (const std::string& fault : c.not_equivalent) EXPECT_NE(run(fault), "equivalent") << fault << " on " << c.scene;
  for (const std::string& fault : c.reported) run(fault);
}

INSTANTIATE_TEST_SUITE_P(
    CompareAnyScene, ValidationFaultsOnNewScene,
    ::testing::Values(
        // A disk with a boundary, forward Euler, turnover, a decision every 5 steps, steps of a
        // quarter of an edge (so the two deposit rules coincide), near-equal faces.
        FaultsOnScene{"repulsion",
                      {"sensor-angle", "no-decay-substep", "turn-every-step", "no-reflect"},
                      {},
                      {"deposit-endpoint", "uniform-face"}},
        // A torus (no boundary), backward Euler (no sub-steps), unequal faces, a decision every 2
        // steps, steps about an edge long.
        FaultsOnScene{"torus_backward",
                      {"sensor-angle", "uniform-face"},
                      {"no-decay-substep", "no-reflect"},
                      {"turn-every-step", "deposit-endpoint"}},
        // The icosphere (no boundary, near-equal faces), forward Euler, a decision every 5 steps,
        // steps a sixth of an edge.
        FaultsOnScene{"default",
                      {"sensor-angle", "no-decay-substep"},
                      {"no-reflect"},
                      {"turn-every-step", "deposit-endpoint", "uniform-face"}},
        // The teapot (19 components, 25 boundary loops, faces of very unequal size), forward Euler,
        // steps of 0.1 m (longer than its faces), a decision every 4 steps: every fault's mechanism
        // is present, and five are judged different (8-32 seeds, 2-3 minutes in all here).
        // no-decay-substep is reported only: its small faces force many forward-Euler sub-steps, so
        // skipping the decay in the first of them raises the mean by 0.9 % (16 seeds: OpenCL 1.0342 U
        // against the reference's 1.0249 U), far inside the 3 % margin. Both arms sit 2.5 % above U
        // because of those sub-steps (the time-discrete model's 1.0250 U); the harness once counted
        // this fault as caught only because it held the faulted arm against U itself (3.4 % off)
        // instead of against the time-discrete model (0.9 % off).
        FaultsOnScene{"teapot",
                      {"sensor-angle", "no-reflect", "turn-every-step", "deposit-endpoint", "uniform-face"},
                      {},
                      {"no-decay-substep"},
                      "teapot.obj"},
        // horn.obj and saddle.obj (tools/scenes/*/make_*.py): graded meshes whose faces differ in
        // area more than a hundredfold, with boundaries; forward Euler, steps of 0.1 m, a decision
        // every 4 steps, like the teapot. On the horn the 15 % wider sensor angle is near the
        // margins (inconclusive at 64 seeds here); the saddle's strongly repelling -60 degree
        // sensors make the pattern depend on the angle, and all six are different there.
        FaultsOnScene{"horn",
                      {"no-decay-substep", "no-reflect", "turn-every-step", "deposit-endpoint", "uniform-face"},
                      {},
                      {},
                      "",
                      {"sensor-angle"}},
        FaultsOnScene{"saddle",
                      {"sensor-angle", "no-decay-substep", "no-reflect", "turn-every-step", "deposit-endpoint",
                       "uniform-face"},
                      {},
                      {}}),
    [](const auto& param_info) { return param_info.param.scene; });

// ---- validation: the paper's convergence claims (Fig. 10b, 10d) as verdicts ----

// resolved.json resolves its diffusion length (sqrt(D / r_dec) = 0.07 m) and its sensor distance
// (0.12 m) at max_circumradius 0.03 and finer.
TEST(ValidationConvergence, TwoFineTriangulationsAreEquivalentAndACoarseOneIsNot) {
  const Verdict fine = compare("resolved", "--arm max_circumradius=0.03 --arm max_circumradius=0.02");
  ASSERT_TRUE(fine.json.is_object()) << fine.run.err;
  std::cout << "0.03 against 0.02: " << summary(fine) << "\n";
  EXPECT_EQ(fine.json["verdict"], "equivalent");
  // The verdict looked at the pattern: a detail energy both arms resolve was decided.
  int decided = 0;
  for (const auto& m : fine.json["metrics"])
    if (m["name"].get<std::string>().rfind("detail_", 0) == 0 && m["verdict"] == "equivalent" && !m.contains("difference_only"))
      ++decided;
  EXPECT_GE(decided, 1);
  const Verdict coarse = compare("resolved", "--arm max_circumradius=0.2 --arm max_circumradius=0.02");
  ASSERT_TRUE(coarse.json.is_object()) << coarse.run.err;
  std::cout << "0.2 against 0.02: " << summary(coarse) << "\n";
  EXPECT_EQ(coarse.json["verdict"], "different");
  // ... and named the detail the coarse arm lost.
  int lost = 0;
  for (const auto& m : coarse.json["metrics"])
    if (m["name"].get<std::string>().rfind("detail_", 0) == 0 && m["verdict"] == "different") ++lost;
  EXPECT_GE(lost, 1);
}

TEST(ValidationConvergence, TwoSmallTimeStepsAreEquivalentAndAnAliasingOneIsNot) {
  const Verdict small = compare("resolved", "--arm time_step=0.005 --arm time_step=0.0025");
  ASSERT_TRUE(small.json.is_object()) << small.run.err;
  std::cout << "0.005 against 0.0025: " << summary(small) << "\n";
  EXPECT_EQ(small.json["verdict"], "equivalent");
  // 0.05 s steps with 20 decisions per second: every step is a decision, and agents move 2.5 cm
  // a step, a fifth of the sensor distance.
  const Verdict aliased = compare("resolved", "--arm time_step=0.05 --arm time_step=0.0025");
  ASSERT_TRUE(aliased.json.is_object()) << aliased.run.err;
  std::cout << "0.05 against 0.0025: " << summary(aliased) << "\n";
  EXPECT_EQ(aliased.json["verdict"], "different");
}

}  // namespace
}  // namespace physarum::testing
