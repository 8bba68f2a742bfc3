// The growth model end to end (api/growth_simulation.hpp, `physarum run`): its scene keys and their
// refusals, a prescribed uniform growth's known answer through the whole model, a stretch map's rest
// state nearly embeddable by a thin sheet (energy as h^3), reaction–diffusion
// on the rest metric (a grown sheet's operators are those of a larger sheet, and the bending does not
// touch the pattern), dilution's conservation, determinism and checkpoints bit for bit, a failed
// solve stopping the run with the last converged sheet written, and both backends agreeing on a
// grown sheet.
#include "api/backend_factory.hpp"
#include "api/session.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/growth/face_growth.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/pattern/pattern_analysis.hpp"
#include "common/setup/reaction_diffusion_build.hpp"
#include "common/run/checkpoint.hpp"
#include "common/shell/hinge_bending.hpp"
#include "common/shell/rest_metric.hpp"
#include "common/simulation/simulation_state.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "killed_run.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace physarum::testing {
namespace {

using nlohmann::json;

SessionOptions quiet(const std::string& backend = "reference") {
  SessionOptions o;
  o.backend = backend;
  o.use_map_cache = false;
  return o;
}

// A small sheet that grows where a prescribed map says (more at the rim: it must buckle), with
// Gray-Scott running in between: every part of a growth step is exercised in well under a second.
json growth_scene() {
  return {{"model", "growth"},
          {"mesh", "shape:disk-10"},
          {"time_step", 1.0},
          {"seed", 5},
          {"maps", {{"rim", {{"axis", "x"}}}, {"stretch", {{"map", "rim"}, {"range", {1.0, 1.3}}}}}},
          {"reaction_diffusion", {{"parameters", {{"F", 0.04}, {"k", 0.06}}},
                                  {"morphogens", {{"u", {{"diffusion", 4e-4}}}, {"v", {{"diffusion", 2e-4}}}}}}},
          {"shell", {{"thickness", 0.02}, {"young_modulus", 1e7}}},
          {"growth", {{"stretch", "stretch"}}},
          {"schedule", {{"reaction_steps", 10}, {"growth_steps", 3}, {"interleaved", true}}}};
}

Session session_of(const json& j, const std::string& backend = "reference") { return Session(scene_from_json(j), quiet(backend)); }

// Each morphogen's amount on the rest metric.
std::vector<double> amounts(const GrowthSimulation& g) {
  const std::vector<double> mass = rest_vertex_masses(g.sheet().topology, g.sheet().rest);
  std::vector<double> total;
  for (int m = 0; m < g.dynamic_layer_count(); ++m) {
    const IntrinsicVertexData<double> u = g.field_values(m);
    double sum = 0.0;
    for (size_t i = 0; i < u.size(); ++i) sum += mass[i] * u[i];
    total.push_back(sum);
  }
  return total;
}

TEST(GrowthScene, BadValuesAreRefusedNamingTheKey) {
  auto refusal = [](const std::function<void(json&)>& edit) {
    json j = growth_scene();
    edit(j);
    return input_error_of([&] { scene_from_json(j); });
  };
  EXPECT_EQ(refusal([](json&) {}), "");
  EXPECT_NE(refusal([](json& j) { j["shell"]["thickness"] = 0; }).find("thickness"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["shell"]["young_modulus"] = -1; }).find("young_modulus"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["shell"]["poisson_ratio"] = 0.5; }).find("poisson_ratio"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["shell"]["poisson_ratio"] = -1.0; }).find("poisson_ratio"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["shell"]["stiffness"] = 1; }).find("unknown field \"stiffness\""), std::string::npos);
  // A growth map of the wrong kind: a direction where a stretch is needed.
  EXPECT_NE(refusal([](json& j) { j["maps"]["out"] = {{"away_from", {0, 0, 0}}}; j["growth"]["stretch"] = "out"; })
                .find("growth.stretch"),
            std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["growth"]["anisotropy"] = {{"direction", "rim"}}; }).find("growth.anisotropy.direction"),
            std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["growth"]["stretch"] = 0; }).find("growth.stretch"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["growth"] = {{"gamma", 0}}; }).find("gamma"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["growth"] = {{"a", "w"}}; }).find("growth.a"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["growth"]["m"] = 1; }).find("growth.m"), std::string::npos);  // law key beside a stretch
  EXPECT_NE(refusal([](json& j) { j["schedule"]["growth_steps"] = 0; }).find("schedule.growth_steps"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["refine"] = {{"max_edge", -1}}; }).find("refine.max_edge"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["dilute"] = "yes"; }).find("dilute"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["steps"] = 10; }).find("schedule"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["parameters"] = json::object(); }).find("reaction_diffusion"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["reaction_diffusion"]["time_step"] = 1.0; }).find("time_step"), std::string::npos);
  EXPECT_NE(refusal([](json& j) { j["model"] = "gray-scott"; }).find("growth model"), std::string::npos);
  // The mesh is the shell's: no intrinsic refinement.
  EXPECT_NE(input_error_of([&] { json j = growth_scene(); j["max_circumradius"] = 0.1; session_of(j); }).find("refine"),
            std::string::npos);
}

// Known answer through the whole model: a uniform stretch s keeps the disk flat and unstressed and
// scales it by s (radius and area), whatever the steps in between.
TEST(GrowthRun, AUniformStretchScalesTheDiskAndKeepsItFlat) {
  json j = growth_scene();
  j["growth"] = {{"stretch", 1.3}};
  j["refine"] = {{"max_edge", 0.15}};  // refinement on the way must not change the answer
  // A flat sheet's bending modes are soft: the perturbation decays only as far as the tolerance asks.
  j["shell"]["tolerance"] = 1e-11;
  Session session = session_of(j);
  GrowthSimulation& g = *session.growth();
  session.step(g.steps_taken() + 33);
  ASSERT_FALSE(g.stopped()) << *g.stopped();
  EXPECT_EQ(g.growth_steps_done(), 3);
  EXPECT_GT(g.sheet().topology.vertex_count, session.surface().input.vertex_count());  // refined
  // Flat (every hinge straight; the plane itself may have turned: the gauge face fixes rigid
  // motions in its own frame) and 1.3 times as wide.
  const auto& x = g.sheet().positions;
  double radius = 0.0, bend = 0.0;
  for (const Eigen::Vector3d& p : x) radius = std::max(radius, (p - x[0]).norm());
  for (const ShellHinge& h : g.sheet().topology.hinges)
    bend = std::max(bend, std::abs(dihedral_angle(x[h.vertices[0]], x[h.vertices[1]], x[h.vertices[2]], x[h.vertices[3]])));
  EXPECT_NEAR(radius, 1.3, 1e-6);
  EXPECT_LT(bend, 1e-6);
  EXPECT_NEAR(rest_area(g.sheet().rest) / g.initial_rest_area(), 1.69, 1e-12);
  for (const double a : g.area_growth()) EXPECT_NEAR(a, 1.69, 1e-9);
  EXPECT_LT(g.records().back().membrane_energy + g.records().back().bending_energy, 1e-9);
}

// A prescribed stretch map grows each edge by the map along it (api/growth_simulation.cpp), so a thin
// sheet can take a shape near the isometric embedding of the map's metric: its energy is nearly all
// bending, which scales as h^3 (8 times less per halving). Grown per face, as before, each shared
// edge got two rest lengths and the unrelievable membrane strain dominated, scaling as h (measured on
// this scene: membrane 6.34 / 3.12 J against bending 0.077 / 0.039 J at h = 10 / 5 mm; per edge,
// 0.0024 / 0.00022 J against 0.032 / 0.0044 J, total energy ratio 7.4).
TEST(GrowthRun, AStretchMapGrowsARestStateThatAThinSheetCanNearlyEmbed) {
  std::vector<GrowthStepRecord> last;
  for (const double h : {0.01, 0.005}) {
    json j = growth_scene();
    j["shell"]["thickness"] = h;
    Session session = session_of(j);
    session.step(33);
    ASSERT_EQ(session.growth()->growth_steps_done(), 3) << "h = " << h;
    last.push_back(session.growth()->records().back());
  }
  EXPECT_LT(last[1].membrane_energy, 0.1 * last[1].bending_energy);
  const double ratio = (last[0].membrane_energy + last[0].bending_energy) / (last[1].membrane_energy + last[1].bending_energy);
  EXPECT_GT(ratio, 6.0);
  EXPECT_LT(ratio, 10.0);
}

// The reaction–diffusion surface is the rest metric: uniformly grown by g, its masses are g^2 times
// and its cotan weights the same as the ungrown sheet's, i.e. it is a sheet g times as large, on
// which a pattern keeps its absolute spacing (set by the rates and kinetics) instead of stretching
// with the tissue.
TEST(GrowthRun, ReactionDiffusionRunsOnTheGrownRestMetric) {
  json j = growth_scene();
  j["growth"] = {{"stretch", 1.5}};
  j["schedule"] = {{"reaction_steps", 0}, {"growth_steps", 1}};
  Session session = session_of(j);
  GrowthSimulation& g = *session.growth();
  const SurfaceDomain before = g.surface().domain;
  session.step(1);
  const SurfaceDomain& after = g.surface().domain;
  ASSERT_EQ(after.vertex_count, before.vertex_count);
  for (int i = 0; i < after.vertex_count; ++i)
    EXPECT_NEAR(after.vertex_mass[static_cast<size_t>(i)], 2.25 * before.vertex_mass[static_cast<size_t>(i)], 1e-12);
  ASSERT_EQ(after.laplacian.value.size(), before.laplacian.value.size());
  for (size_t k = 0; k < after.laplacian.value.size(); ++k)
    EXPECT_NEAR(after.laplacian.value[k], before.laplacian.value[k], 1e-9 * (1 + std::abs(before.laplacian.value[k])));
}

// A Gray-Scott spot pattern on the rest metric of a disk grown uniformly by 1.5 (before any pattern
// forms) and on the ungrown unit disk: the spots keep their absolute spacing (set by the diffusion
// rates and the kinetics) within 5 %, rather than spreading 1.5 times apart with the tissue; the
// grown disk simply holds more of them.
double mean_spot_spacing(double growth, const std::string& disk, double max_edge) {
  // As many seed spots per unit area on either disk: both fill in the same time.
  const json j = {{"model", "gray-scott"},
                  {"mesh", disk},
                  {"time_step", 1.0},
                  {"seed", 4},
                  {"parameters", {{"F", 0.035}, {"k", 0.065}}},  // spots that divide until they fill the disk
                  {"morphogens", {{"u", {{"diffusion", 5e-5}}}, {"v", {{"diffusion", 2.5e-5}}}}},
                  {"initial", {{"noise", 0.02}, {"spots", {{"count", static_cast<int>(40 * growth * growth)}, {"radius", 0.06}, {"values", {{"u", 0.5}, {"v", 0.25}}}}}}}};
  const Scene scene = scene_from_json(j);
  GrowingSheet sheet = initial_sheet(scene);
  for (Eigen::Matrix2d& metric : sheet.rest.face_metric) metric *= growth * growth;
  for (Eigen::Vector3d& p : sheet.positions) p *= growth;  // the equilibrium of a uniform growth
  // Refined back to a fine resolution, as a growth run keeps it (refine.max_edge): the spots' spacing
  // depends a little on the resolution (a few per cent between 6 and 10 edges across it).
  refine_sheet(sheet, max_edge);
  const PreparedSurface surface = sheet_surface(sheet, "disk");
  auto backend = make_reaction_diffusion_backend(BackendChoice::Reference, nullptr, surface.domain,
                                                 build_reaction_diffusion_system(scene, surface, EvaluatedMaps{}));
  backend->run(16000);
  const IntrinsicVertexData<double> v = backend->field_values(1);
  PatternAnalysisOptions options;
  options.min_area = 1e-3;
  const PatternAnalysis analysis =
      analyze_pattern(surface.input, InputVertexData<double>(std::vector<double>(v.begin(), v.end())), options);
  std::vector<double> distances;
  for (const SpotPair& pair : analysis.pairs) distances.push_back(pair.distance);
  EXPECT_GT(distances.size(), 100u);  // about 140 pairs on the unit disk (spacing ~0.26 m), 300 grown
  return mean_and_std(distances).mean;
}

// About four minutes on 2 cores (two fine disks, the grown one 2.25 times as large): in the
// validation suite.
TEST(ValidationGrowth, APatternKeepsItsAbsoluteSpacingOnAGrownSheet) {
  // Both at about the same resolution (rest edges 0.017 to 0.02 m): the unit disk of 60 rings, and
  // the disk of 40 rings grown by 1.5 and refined to edges of at most 0.02.
  const double ungrown = mean_spot_spacing(1.0, "shape:disk-60", 1.0), grown = mean_spot_spacing(1.5, "shape:disk-40", 0.02);
  RecordProperty("spacing_ungrown", std::to_string(ungrown));
  RecordProperty("spacing_grown", std::to_string(grown));
  EXPECT_NEAR(grown / ungrown, 1.0, 0.05) << "spacing " << ungrown << " on the unit disk, " << grown << " grown by 1.5";
}

// The pattern depends on the tissue, not on its shape: the same growth with a shell 5 times thinner
// (so 125 times easier to bend: another buckled shape) gives the same morphogens to the last bit.
TEST(GrowthRun, ThePatternDoesNotDependOnTheBending) {
  json thick = growth_scene(), thin = growth_scene();
  thin["shell"]["thickness"] = 0.004;
  Session a = session_of(thick), b = session_of(thin);
  a.step(33);
  b.step(33);
  ASSERT_EQ(a.growth()->growth_steps_done(), 3);
  ASSERT_EQ(b.growth()->growth_steps_done(), 3);
  double shape_difference = 0.0;
  for (size_t i = 0; i < a.growth()->sheet().positions.size(); ++i)
    shape_difference = std::max(shape_difference, (a.growth()->sheet().positions[i] - b.growth()->sheet().positions[i]).norm());
  EXPECT_GT(shape_difference, 1e-3);  // the shells did take other shapes
  for (int m = 0; m < 2; ++m) EXPECT_EQ(a.field(m).values(), b.field(m).values()) << "morphogen " << m;
}

TEST(GrowthRun, DilutionConservesEachMorphogensAmountThroughAGrowthStep) {
  json j = growth_scene();
  j["dilute"] = true;
  Session session = session_of(j);
  GrowthSimulation& g = *session.growth();
  for (int growth_step = 0; growth_step < 3; ++growth_step) {
    session.step(10);  // reaction steps
    const std::vector<double> before = amounts(g);
    const double area = rest_area(g.sheet().rest);
    session.step(1);  // a growth step
    ASSERT_EQ(g.growth_steps_done(), growth_step + 1);
    EXPECT_GT(rest_area(g.sheet().rest), 1.01 * area);
    const std::vector<double> after = amounts(g);
    for (size_t m = 0; m < before.size(); ++m) EXPECT_NEAR(after[m], before[m], 1e-9 * std::abs(before[m])) << "morphogen " << m;
  }
  // Without dilution the concentrations stay, and the amounts grow with the tissue.
  j["dilute"] = false;
  Session plain = session_of(j);
  plain.step(10);
  const std::vector<double> before = amounts(*plain.growth());
  plain.step(1);
  EXPECT_GT(amounts(*plain.growth())[0], 1.01 * before[0]);
}

// A state's bytes without the wall-clock seconds (model array 6, the step records, of which the
// seconds are the 11th of 12 numbers each, and the header's 8th number, the reaction seconds): they
// are timings, not results.
std::string state_bytes(const Session& session) {
  SimulationState state = session.backend().save_state();
  std::vector<double>& records = state.model_arrays.at(6);
  for (size_t k = 10; k < records.size(); k += 12) records[k] = 0.0;
  state.model_arrays.at(0).at(7) = 0.0;  // the header's reaction seconds: a timing too
  return checkpoint_bytes({}, state);
}

// The same seed gives the same bytes; a checkpoint taken mid-run (after a growth step, and between
// reaction steps) continues bit for bit, refinement included.
TEST(GrowthRun, DeterministicAndCheckpointsContinueBitForBit) {
  json j = growth_scene();
  j["refine"] = {{"max_edge", 0.12}};
  TempDir dir;
  Session whole = session_of(j);
  whole.step(33);
  Session again = session_of(j);
  again.step(33);
  EXPECT_TRUE(state_bytes(whole) == state_bytes(again));
  for (const long long at : {11LL, 15LL}) {
    Session first = session_of(j);
    first.step(at);
    const std::string path = (dir.path / ("at" + std::to_string(at) + ".bin")).string();
    first.save(path);
    Session resumed = session_of(j);
    resumed.restore(path);
    resumed.step(33 - at);
    EXPECT_TRUE(state_bytes(resumed) == state_bytes(whole)) << "resumed after step " << at;
  }
  EXPECT_GT(whole.growth()->sheet().topology.vertex_count, whole.surface().input.vertex_count());
}

// Both backends' reaction–diffusion on a grown (refined, unevenly grown) sheet agree as the
// reaction–diffusion backend tests require of any surface.
TEST(GrowthRun, BothBackendsAgreeOnAGrownSheet) {
  try {
    opencl::make_compute_context("");
  } catch (const std::exception& e) {
    GTEST_SKIP() << "no OpenCL device: " << e.what();
  }
  json j = growth_scene();
  j["refine"] = {{"max_edge", 0.12}};
  j["schedule"] = {{"reaction_steps", 200}, {"growth_steps", 2}, {"interleaved", true}};
  Session reference = session_of(j, "reference"), device = session_of(j, "opencl");
  reference.step(402);
  device.step(402);
  ASSERT_EQ(reference.growth()->growth_steps_done(), 2);
  for (int m = 0; m < 2; ++m) {
    const auto x = reference.field(m), y = device.field(m);
    ASSERT_EQ(x.size(), y.size());
    double worst = 0.0;
    for (size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(x[i] - y[i]));
    EXPECT_LT(worst, 1e-4) << "morphogen " << m;
  }
}

// A solve that cannot converge (one Newton iteration allowed) stops the run: `physarum run` writes
// the last converged sheet (here the initial one), says which step failed and what to change, and
// exits with 1.
TEST(GrowthRun, AFailedSolveStopsTheRunKeepingTheLastConvergedSheet) {
  TempDir dir;
  json j = growth_scene();
  j["shell"]["max_iterations"] = 1;
  std::ofstream(dir.path / "scene.json") << j.dump();
  const CommandResult r = run_physarum("run " + quoted(dir.path / "scene.json") + " --backend reference --out " + quoted(dir.path / "out"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("growth step 1 of 3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("8 sub-steps"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("residual"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("schedule.growth_steps"), std::string::npos) << r.err;
  std::ifstream in(dir.path / "out" / "run.json");
  ASSERT_TRUE(in.good());
  const json run = json::parse(in);
  EXPECT_EQ(run["growth_steps"], 0);
  EXPECT_EQ(run["steps"], 10);
  EXPECT_DOUBLE_EQ(run["area_growth"].get<double>(), 1.0);
  EXPECT_TRUE(std::filesystem::exists(dir.path / "out" / "fields_full.ply"));
}

// `physarum run --checkpoint-every` killed at a random moment and resumed writes the uninterrupted
// run's bytes: the checkpoint holds the whole sheet (shape, rest state, refinement, records).
TEST(GrowthRun, AKilledRunResumesToTheUninterruptedRunsBytes) {
  TempDir dir;
  json j = growth_scene();
  j["schedule"]["growth_steps"] = 8;
  j["refine"] = {{"max_edge", 0.12}};
  std::ofstream(dir.path / "scene.json") << j.dump();
  auto args = [&](const std::filesystem::path& out) {
    return std::vector<std::string>{"run", (dir.path / "scene.json").string(), "--backend", "reference", "--out", out.string()};
  };
  std::string whole_args;
  for (const std::string& a : args(dir.path / "whole")) whole_args += quoted(std::filesystem::path(a)) + " ";
  ASSERT_EQ(run_physarum(whole_args).exit_code, 0);
  const std::filesystem::path killed = dir.path / "killed";
  std::vector<std::string> killed_args = args(killed);
  killed_args.insert(killed_args.end(), {"--checkpoint-every", "4"});  // every 4 steps (time_step 1 s)
  const unsigned seed = std::random_device{}();
  ASSERT_TRUE(run_and_kill(killed_args, killed / "checkpoint.bin", seed)) << "finished before the kill (seed " << seed << ")";
  const CommandResult resumed = run_physarum("run --resume " + quoted(killed));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  for (const char* file : {"morphogens.ply", "fields_full.ply", "stats.csv", "preview.png", "result.glb"})
    EXPECT_TRUE(bytes_of(killed / file) == bytes_of(dir.path / "whole" / file)) << file << " (kill delay seed " << seed << ")";
  const json run = json::parse(std::ifstream(killed / "run.json"));
  EXPECT_GT(run["resumed_from_step"].get<long long>(), 0);
  EXPECT_EQ(run["growth_steps"], 8);
}

// `physarum run` writes the grown sheet and the records DESIGN.md promises.
TEST(GrowthRun, TheRunWritesTheGrownSheetAndItsRecords) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << growth_scene().dump();
  const CommandResult r = run_physarum("run " + quoted(dir.path / "scene.json") + " --backend reference --frames 3 --out " +
                                       quoted(dir.path / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json run = json::parse(std::ifstream(dir.path / "out" / "run.json"));
  EXPECT_EQ(run["model"], "growth");
  EXPECT_EQ(run["steps"], 33);
  EXPECT_EQ(run["growth_steps"], 3);
  EXPECT_EQ(run["newton_iterations"].size(), 3u);
  EXPECT_GT(run["area_growth"].get<double>(), 1.05);
  EXPECT_TRUE(run["energy"].contains("membrane"));
  for (const char* file : {"morphogens.ply", "fields_full.ply", "preview.png", "result.glb", "stats.csv",
                           "frames/frame_0003.png", "frames/frame_0003.ply", "frames.gif"})
    EXPECT_TRUE(std::filesystem::exists(dir.path / "out" / file)) << file;
  // The outputs are the grown shape (no longer flat), with the area growth beside the morphogens.
  const PlyFields ply = read_ply_fields((dir.path / "out" / "fields_full.ply").string());
  double low = 0.0, high = 0.0;
  for (const Eigen::Vector3d& p : ply.mesh.positions) low = std::min(low, p.z()), high = std::max(high, p.z());
  EXPECT_GT(high - low, 0.01);
  const std::vector<double>& area_growth = ply.property("area_growth");
  EXPECT_GT(*std::max_element(area_growth.begin(), area_growth.end()), 1.1);
  EXPECT_EQ(ply.property("u").size(), ply.mesh.positions.size());
  // `physarum render` re-colours it.
  EXPECT_EQ(run_physarum("render " + quoted(dir.path / "out") + " --out " + quoted(dir.path / "render")).exit_code, 0);
  // --steps only restates the schedule, the run's length.
  EXPECT_EQ(run_physarum("run " + quoted(dir.path / "scene.json") + " --steps 33 --backend reference --out " + quoted(dir.path / "y")).exit_code, 0);
  const CommandResult steps = run_physarum("run " + quoted(dir.path / "scene.json") + " --steps 5 --out " + quoted(dir.path / "x"));
  EXPECT_EQ(steps.exit_code, 2);
  EXPECT_NE(steps.err.find("schedule"), std::string::npos) << steps.err;
}

}  // namespace
}  // namespace physarum::testing

namespace physarum::testing {
namespace {

// What the library and the harness do with a growth scene they cannot take: one line naming it, not
// the internal error of a model's settings asked of another model (issue 55).
TEST(GrowthScene, CompareAndMakeBackendRefuseItInOneLine) {
  const std::string scene = std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/growth_cap.json";
  const CommandResult r = run_physarum("compare " + quoted(std::filesystem::path(scene)));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("growth scene"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  const Scene loaded = load_scene(scene);
  const PreparedSurface surface = prepare_scene_surface(loaded);
  const std::string message = input_error_of([&] { make_backend(BackendChoice::Reference, nullptr, surface, loaded); });
  EXPECT_NE(message.find("Session"), std::string::npos) << message;
}

}  // namespace
}  // namespace physarum::testing
