// The serial reference simulation as a whole: the U metric of Eq. 5, time-step independence,
// reproducibility, and `physarum run` as a user runs it.
#include "common/model/discrete_steady_state.hpp"
#include "common/setup/agent_inputs.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/scene/scene.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/model/vertex_parameters.hpp"
#include "reference/agent_simulation.hpp"
#include "delaunay_domain.hpp"
#include "model_scene.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace physarum {
namespace {

using testing::model_scene;

constexpr double kDegree = std::numbers::pi / 180.0;

using testing::delaunay_domain;
using testing::quoted;


// Time average of the area-weighted mean over steps [first, last] of a run whose field starts at U.
double averaged_mean(const SurfaceDomain& domain, const Scene& scene, int first, int last) {
  ReferenceAgentSimulation sim(domain, constant_parameters(scene, domain), simulation_settings(scene));
  const double U = uniform_steady_state(scene, domain.total_area);
  sim.fill_field(U);
  double sum = 0.0;
  for (int s = 1; s <= last; ++s) {
    sim.step();
    if (s >= first) sum += area_weighted_mean(sim.field(), domain.vertex_mass);
  }
  return sum / (last - first + 1) / U;
}

// Why the mean is exactly U in expectation: every step the agents deposit N r_dep dt times the
// fraction of them that are active (exp(-t_a / tau) in expectation, thanks to the steady-state
// initial ages), diffusion conserves the total amount (the Laplacian's columns sum to zero), and the
// deposits enter each Euler scheme as its source term, so the total amount's fixed point is
// deposit / (r_dec dt) -- exactly U A (see reference/agent_simulation.hpp). What remains is noise: the
// number of active agents fluctuates by ~1% (N = 5000, p = 0.67), with a correlation time ~tau =
// 0.2 s, and averaging over 8 s brings that to ~0.2%. r_dec dt = 2.5% makes a wrongly ordered
// source term (U (1 -+ r_dec dt)) fail the 1% bound. Without turnover the input is deterministic.
void expect_mean_is_U(const std::string& spec, Integrator integrator) {
  const SurfaceDomain domain = delaunay_domain(spec);
  EXPECT_NEAR(averaged_mean(domain, model_scene(5000, 0.01, 0.2, integrator), 200, 1000), 1.0, 0.01)
      << spec << " with turnover";
  // Without turnover agents start newborn and deposit only after t_a, then the field relaxes back
  // at rate r_dec: after 8 s the deficit is below exp(-2.5 * 7.9) of U.
  EXPECT_NEAR(averaged_mean(domain, model_scene(500, 0.01, std::nullopt, integrator), 800, 1000), 1.0, 0.01)
      << spec << " without turnover";
}


TEST(ReferenceAgentSimulation, MeanIsUOnAClosedSurfaceForwardEuler) { expect_mean_is_U("shape:sphere", Integrator::Forward); }
TEST(ReferenceAgentSimulation, MeanIsUOnAClosedSurfaceBackwardEuler) { expect_mean_is_U("shape:sphere", Integrator::Backward); }
TEST(ReferenceAgentSimulation, MeanIsUWithABoundaryForwardEuler) { expect_mean_is_U("shape:square", Integrator::Forward); }
TEST(ReferenceAgentSimulation, MeanIsUWithABoundaryBackwardEuler) { expect_mean_is_U("shape:square", Integrator::Backward); }

// k dt = 0.1 with a diffusion fast enough that forward Euler takes several sub-steps: the derivation
// puts the mean ~4 % above U (more than the harness's 3 % margin); the run must land there, within
// the noise of ~0.3 % (5,000 agents, 600 steps: the bound of expect_mean_is_U in
// test_reference_simulation.cpp), and backward Euler on the same scene at U.
TEST(ReferenceAgentSimulation, DiscreteSteadyStateForwardEulerInSubStepsSettlesWhereDerived) {
  const SurfaceDomain domain = delaunay_domain("shape:sphere");
  Scene scene = model_scene(5000, 0.04, 0.2, Integrator::Forward);
  scene.agent_model().parameters[Param::activation_time] = 0.08;  // two whole steps: no activation factor
  scene.agent_model().parameters[Param::diffuse_rate] = 0.2;
  const double expected = expected_mean_over_U(scene, constant_parameters(scene, domain), domain);
  ASSERT_GT(expected, 1.035) << "the scene must take enough sub-steps to show the effect";
  EXPECT_NEAR(averaged_mean(domain, scene, 200, 800), expected, 0.01);
  scene.agent_model().integrator = Integrator::Backward;
  EXPECT_EQ(expected_mean_over_U(scene, constant_parameters(scene, domain), domain), 1.0);
  EXPECT_NEAR(averaged_mean(domain, scene, 200, 800), 1.0, 0.01);
}

// Short lives (tau = 0.05 s) and t_a = 3.33 steps: the first depositing step of an agent deposits
// two thirds of a step, and the surviving fraction is geometric per step: ~4 % above Eq. 5.
TEST(ReferenceAgentSimulation, DiscreteSteadyStateFractionalActivationStepSettlesWhereDerived) {
  const SurfaceDomain domain = delaunay_domain("shape:sphere");
  Scene scene = model_scene(20000, 0.03, 0.05, Integrator::Backward);
  const double expected = expected_mean_over_U(scene, constant_parameters(scene, domain), domain);
  ASSERT_GT(expected, 1.03);
  EXPECT_NEAR(averaged_mean(domain, scene, 200, 800), expected, 0.01);
}

// Steady-state statistics averaged over the second half of a 4 s run.
struct SteadyStatistics {
  double mean = 0.0;
  double coverage = 0.0;  // area fraction above U
};

SteadyStatistics steady_statistics(const SurfaceDomain& domain, Scene scene, std::uint32_t seed, double seconds) {
  scene.seed = seed;
  ReferenceAgentSimulation sim(domain, constant_parameters(scene, domain), simulation_settings(scene));
  const double U = uniform_steady_state(scene, domain.total_area);
  const auto steps = std::llround(seconds / scene.time_step);
  SteadyStatistics r;
  int samples = 0;
  for (long long s = 1; s <= steps; ++s) {
    sim.step();
    if (2 * s > steps && s % std::llround(0.05 / scene.time_step) == 0) {
      const FieldStatistics f = compute_field_statistics(sim.field(), domain.vertex_mass, U);
      r.mean += f.mean / U;
      r.coverage += f.coverage[1];
      ++samples;
    }
  }
  r.mean /= samples;
  r.coverage /= samples;
  return r;
}

void expect_time_step_independence(Integrator integrator) {
  const SurfaceDomain domain = delaunay_domain("shape:sphere");
  Scene scene = model_scene(3000, 0.01, 0.5, integrator);
  scene.agent_model().parameters[Param::decay_rate] = 1.0;
  const int seeds = 4;
  std::vector<SteadyStatistics> coarse, fine;
  for (int s = 0; s < seeds; ++s) {
    coarse.push_back(steady_statistics(domain, scene, 100 + s, 4.0));
    Scene halved = scene;
    halved.time_step = scene.time_step / 2;
    fine.push_back(steady_statistics(domain, halved, 200 + s, 4.0));
  }
  auto mean_sd = [](const std::vector<SteadyStatistics>& v, double SteadyStatistics::*field) {
    double m = 0, q = 0;
    for (const auto& x : v) m += x.*field;
    m /= v.size();
    for (const auto& x : v) q += (x.*field - m) * (x.*field - m);
    return std::pair{m, std::sqrt(q / (v.size() - 1))};
  };
  for (auto field : {&SteadyStatistics::mean, &SteadyStatistics::coverage}) {
    const auto [m1, s1] = mean_sd(coarse, field);
    const auto [m2, s2] = mean_sd(fine, field);
    // Welch-style bound: 4 standard errors of the difference, with a small floor so a near-zero
    // spread (the mean is almost deterministic) does not demand bit equality.
    const double bound = 4.0 * std::sqrt((s1 * s1 + s2 * s2) / seeds) + 0.005;
    EXPECT_NEAR(m1, m2, bound) << (field == &SteadyStatistics::mean ? "mean/U" : "coverage above U") << ": dt "
                               << scene.time_step << " gives " << m1 << " +- " << s1 << ", dt/2 gives " << m2
                               << " +- " << s2;
  }
}

TEST(ReferenceAgentSimulation, HalvingTheTimeStepKeepsMeanAndCoverageWithinSeedSpread) {
  expect_time_step_independence(Integrator::Forward);
}
TEST(ReferenceAgentSimulation, HalvingTheTimeStepKeepsMeanAndCoverageWithinSeedSpreadBackwardEuler) {
  expect_time_step_independence(Integrator::Backward);
}

TEST(ReferenceAgentSimulation, SameSeedSameRunDifferentSeedDifferentPattern) {
  const SurfaceDomain domain = delaunay_domain("shape:sphere");
  const Scene scene = model_scene(1000, 0.01, 0.5, Integrator::Forward);
  const VertexParameters params = constant_parameters(scene, domain);
  ReferenceAgentSimulation a(domain, params, simulation_settings(scene)), b(domain, params, simulation_settings(scene));
  Scene other_seed = scene;
  other_seed.seed = scene.seed + 1;
  ReferenceAgentSimulation c(domain, params, simulation_settings(other_seed));
  a.run(150);
  b.run(150);
  c.run(150);
  EXPECT_EQ(a.field(), b.field());
  EXPECT_EQ(a.agents().position, b.agents().position);
  // A different seed grows a different pattern: the fields differ by a sizeable fraction of their norm.
  double diff = 0, norm = 0;
  for (size_t i = 0; i < a.field().size(); ++i) {
    diff += std::pow(a.field()[i] - c.field()[i], 2);
    norm += std::pow(a.field()[i], 2);
  }
  EXPECT_GT(std::sqrt(diff / norm), 0.2);
}

// ---- the command line ------------------------------------------------------------------------

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_scene(const std::filesystem::path& path, const std::string& extra = "") {
  std::ofstream(path) << R"({
  "mesh": "shape:square", "scale_to_area": 2.0, "agents": 400, "time_step": 0.01,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward", "seed": 3)"
                      << extra << "\n}\n";
}

TEST(ReferenceRunCommand, WritesTheFourOutputsReproducibly) {
  testing::TempDir dir;
  write_scene(dir.path / "scene.json");
  const std::string scene = quoted(dir.path / "scene.json");
  const auto out1 = dir.path / "a", out2 = dir.path / "b", out3 = dir.path / "c";
  const auto r1 = testing::run_physarum("run " + scene + " --backend reference --steps 200 --out " + quoted(out1));
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  const auto r2 = testing::run_physarum("run " + scene + " --backend reference --steps 200 --out " + quoted(out2));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const auto r3 = testing::run_physarum("run " + scene + " --backend reference --sim-time 2 --seed 4 --out " + quoted(out3));
  ASSERT_EQ(r3.exit_code, 0) << r3.err;
  // stderr is not a terminal: no progress bar; its one line is the note that the square has no UVs
  // to bake a texture onto.
  EXPECT_EQ(r1.err, "physarum run: note: shape:square has no texture coordinates (UVs); no texture.png is written\n")
      << "no progress bar expected";

  // Same seed: byte-identical results (run.json differs only in its timings).
  for (const char* name : {"pheromone.ply", "stats.csv", "preview.png"}) {
    ASSERT_TRUE(std::filesystem::exists(out1 / name)) << name;
    EXPECT_EQ(slurp(out1 / name), slurp(out2 / name)) << name;
    EXPECT_NE(slurp(out1 / name), slurp(out3 / name)) << name << " (different seed)";
  }
  nlohmann::json j1 = nlohmann::json::parse(slurp(out1 / "run.json"));
  nlohmann::json j2 = nlohmann::json::parse(slurp(out2 / "run.json"));
  for (const char* key : {"backend", "device", "steps", "sim_time", "seconds", "agent_steps_per_second",
                          "face_crossings_per_agent_step", "U", "mean", "intrinsic_vertices", "intrinsic_faces"})
    EXPECT_TRUE(j1.contains(key)) << key;
  for (const char* timing : {"seconds", "agent_steps_per_second", "face_crossings_per_second"})
    j1.erase(timing), j2.erase(timing);
  j1.erase("scene_file"), j2.erase("scene_file");
  EXPECT_EQ(j1, j2);
  EXPECT_EQ(j1["backend"], "reference");
  EXPECT_EQ(j1["steps"], 200);
  EXPECT_NEAR(j1["sim_time"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(j1["area"].get<double>(), 2.0, 1e-9);  // scale_to_area
  // U of Eq. 5 for this scene: 400 * 1 / (1 * 2) * exp(-0.2 / 1).
  EXPECT_NEAR(j1["U"].get<double>(), 200.0 * std::exp(-0.2), 1e-9);
  EXPECT_GT(j1["face_crossings_per_agent_step"].get<double>(), 0.0);
  EXPECT_EQ(j1["parameters"]["agents"], 400);
  EXPECT_EQ(nlohmann::json::parse(slurp(out3 / "run.json"))["steps"], 200);  // --sim-time 2 at dt 0.01

  // stats.csv: the exact header, then about 100 rows of increasing time ending at the run's end.
  std::istringstream csv(slurp(out1 / "stats.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "time,mean,U,coverage_0.5U,coverage_1U,coverage_2U");
  int rows = 0;
  double last_time = -1;
  while (std::getline(csv, line)) {
    const double t = std::stod(line.substr(0, line.find(',')));
    EXPECT_GT(t, last_time);
    last_time = t;
    ++rows;
  }
  EXPECT_GE(rows, 90);
  EXPECT_LE(rows, 202);
  EXPECT_NEAR(last_time, 2.0, 1e-9);
  // PLY on the INPUT mesh (shape:square: 33 x 33 vertices), in its own coordinates.
  const std::string ply = slurp(out1 / "pheromone.ply");
  EXPECT_NE(ply.find("element vertex 1089"), std::string::npos);
}

TEST(ReferenceRunCommand, BadSceneExitsOneAndWritesNothing) {
  testing::TempDir dir;
  write_scene(dir.path / "scene.json", R"(, "sensor_angel": 10)");
  const auto out = dir.path / "out";
  const auto r = testing::run_physarum("run " + quoted(dir.path / "scene.json") + " --steps 5 --out " + quoted(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("sensor_angel"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));

  write_scene(dir.path / "good.json");
  const auto both = testing::run_physarum("run " + quoted(dir.path / "good.json") + " --steps 5 --sim-time 1 --out " + quoted(out));
  EXPECT_EQ(both.exit_code, 2) << both.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The shipped example scenes load; a scene whose mesh lives in ../shared/meshes is skipped (not
// failed) when that file is absent. Each shipped scene carries its own run length, so it runs as is.
class ShippedScenesLoad : public ::testing::TestWithParam<const char*> {};

TEST_P(ShippedScenesLoad, WithARunLength) {
  const std::filesystem::path p = std::filesystem::path(PHYSARUM_SOURCE_DIR) / "tools" / "scenes" / GetParam();
  ASSERT_TRUE(std::filesystem::exists(p)) << p;
  const std::string mesh = nlohmann::json::parse(slurp(p)).at("mesh").get<std::string>();
  if (mesh.rfind("shape:", 0) != 0) {
    const std::filesystem::path mesh_path = (p.parent_path() / mesh).lexically_normal();
    if (!std::filesystem::exists(mesh_path)) GTEST_SKIP() << "mesh " << mesh_path << " of " << p << " is absent";
  }
  const Scene s = load_scene(p.string());
  EXPECT_GT(s.agent_model().agents, 0);
  EXPECT_TRUE(s.steps || s.sim_time) << "a shipped scene must run without --steps / --sim-time";
}

INSTANTIATE_TEST_SUITE_P(ReferenceRunCommand, ShippedScenesLoad,
                         ::testing::Values("default.json", "prism.json", "spot.json", "bunny.json"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                           const std::string name = param_info.param;
                           return name.substr(0, name.find('.'));
                         });

// The prism scene is the setup of the paper's Fig. 10(a) as far as the paper states it (Sec. 5,
// resolution study): the octagonal prism, a maximum circumradius at or below 0.03 m (no visible
// change below it), 1000 to 2000 agents (1000 suffice, 2000 is the largest count shown) and a time
// step at or below 0.001 s (the three smallest of 0.02 ... 0.0001 s converge).
TEST(ReferenceRunCommand, PrismSceneFollowsFigure10a) {
  const Scene s = load_scene((std::filesystem::path(PHYSARUM_SOURCE_DIR) / "tools" / "scenes" / "prism.json").string());
  EXPECT_EQ(s.mesh, "shape:octagonal-prism");
  EXPECT_FALSE(s.scale_to_area) << "the prism is used at its own size, in metres";
  ASSERT_TRUE(s.max_circumradius);
  EXPECT_LE(*s.max_circumradius, 0.03);
  EXPECT_GE(s.agent_model().agents, 1000);
  EXPECT_LE(s.agent_model().agents, 2000);
  EXPECT_LE(s.time_step, 0.001);
}

// What a user runs first: the built-in default scene, shortened to 20 steps, writes the five outputs.
TEST(ReferenceRunCommand, DefaultSceneRunsEndToEnd) {
  testing::TempDir dir;
  const auto scene = std::filesystem::path(PHYSARUM_SOURCE_DIR) / "tools" / "scenes" / "default.json";
  const auto out = dir.path / "out";
  const auto r = testing::run_physarum("run " + quoted(scene) + " --steps 20 --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"pheromone.ply", "result.glb", "stats.csv", "preview.png", "run.json"}) {
    ASSERT_TRUE(std::filesystem::is_regular_file(out / name)) << name;
    EXPECT_GT(std::filesystem::file_size(out / name), 0u) << name;
  }
  const nlohmann::json j = nlohmann::json::parse(slurp(out / "run.json"));
  EXPECT_EQ(j["steps"], 20);
  EXPECT_EQ(j["parameters"]["mesh"], "shape:sphere");
  EXPECT_EQ(slurp(out / "stats.csv").substr(0, 50), "time,mean,U,coverage_0.5U,coverage_1U,coverage_2U\n");
}

// A scene naming a mesh file that does not exist: exit 1, the message names the key and the file,
// and the output folder is never created.
TEST(ReferenceRunCommand, MissingMeshFileInASceneExitsOneAndWritesNothing) {
  testing::TempDir dir;
  std::string scene_text = slurp(std::filesystem::path(PHYSARUM_SOURCE_DIR) / "tools" / "scenes" / "default.json");
  const std::string shape = "\"shape:sphere\"";
  ASSERT_NE(scene_text.find(shape), std::string::npos);
  scene_text.replace(scene_text.find(shape), shape.size(), "\"meshes/no-such-bunny.obj\"");
  std::ofstream(dir.path / "scene.json") << scene_text;
  const auto out = dir.path / "out";
  const auto r = testing::run_physarum("run " + quoted(dir.path / "scene.json") + " --steps 5 --out " + quoted(out));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("no-such-bunny.obj"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'mesh'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find((dir.path / "meshes" / "no-such-bunny.obj").string()), std::string::npos)
      << "the message says where it looked (relative to the scene file): " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Vertex positions of a binary little-endian PLY as write_field_ply lays it out (x y z value as
// floats, then r g b bytes: 19 bytes a vertex).
std::vector<Eigen::Vector3d> ply_vertex_positions(const std::string& bytes) {
  const size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  int count = -1;
  for (std::string line; std::getline(header, line);)
    if (line.rfind("element vertex ", 0) == 0) count = std::stoi(line.substr(15));
  std::vector<Eigen::Vector3d> positions;
  size_t at = end + std::string("end_header\n").size();
  for (int v = 0; v < count && at + 19 <= bytes.size(); ++v, at += 19) {
    float xyz[3];
    std::memcpy(xyz, bytes.data() + at, sizeof xyz);
    positions.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
  return positions;
}

// The PLY carries the field on the INPUT mesh: with refinement (vertices inserted) and scale_to_area
// (the simulation runs on a copy scaled by sqrt(2)), it still has the input's vertices, in the
// input's own coordinates.
TEST(ReferenceRunCommand, PlyIsTheUnscaledInputMeshAfterRefinementAndScaling) {
  testing::TempDir dir;
  // shape:square is the unit square (area 1) with 33 x 33 vertices; at area 2 its cells are 0.044 m,
  // whose triangles have a circumradius of 0.031 m > 0.02 m, so refinement must insert vertices.
  write_scene(dir.path / "scene.json", R"(, "max_circumradius": 0.02)");
  const auto out = dir.path / "out";
  const auto r = testing::run_physarum("run " + quoted(dir.path / "scene.json") + " --steps 10 --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(out / "run.json"));
  const InputMesh input = load_mesh("shape:square");
  ASSERT_EQ(input.vertex_count(), 1089);
  ASSERT_GT(j["intrinsic_vertices"].get<int>(), input.vertex_count()) << "the scene must insert vertices";
  EXPECT_NEAR(j["area"].get<double>(), 2.0, 1e-9);

  const std::vector<Eigen::Vector3d> ply = ply_vertex_positions(slurp(out / "pheromone.ply"));
  ASSERT_EQ(ply.size(), static_cast<size_t>(input.vertex_count()));
  double worst = 0.0;
  for (int v = 0; v < input.vertex_count(); ++v) worst = std::max(worst, (ply[v] - input.positions[v]).norm());
  EXPECT_LT(worst, 1e-6) << "PLY positions differ from the input's (float precision allows ~6e-8)";
}

// Without turnover (mean_lifetime null) agents start newborn and never respawn, so nothing is
// deposited while every agent is younger than activation_time: the field is exactly 0 up to then.
// In step k an agent of age (k - 1) dt deposits the fraction of the step past t_a (active_fraction),
// which is 0 for k <= 19 at t_a = 0.2, dt = 0.01 (step 20 may see a rounding-sized sliver) and 1
// from step 21 on.
void expect_newborn_start_without_turnover(Integrator integrator) {
  const SurfaceDomain domain = delaunay_domain("shape:sphere");
  Scene scene = model_scene(1000, 0.01, std::nullopt, integrator);
  scene.agent_model().parameters[Param::activation_time] = 0.2;
  ReferenceAgentSimulation sim(domain, constant_parameters(scene, domain), simulation_settings(scene));
  for (double age : sim.agents().age) ASSERT_EQ(age, 0.0) << "agents start newborn without turnover";
  for (int k = 1; k <= 19; ++k) {
    sim.step();
    for (double u : sim.field()) ASSERT_EQ(u, 0.0) << "step " << k << " (t = " << sim.time() << " s)";
  }
  sim.run(2);  // steps 20, 21
  EXPECT_GT(area_weighted_mean(sim.field(), domain.vertex_mass), 0.0) << "agents older than t_a deposit";
  sim.run(279);  // to 3 s: with a 1 s lifetime this would be ~3000 respawns
  EXPECT_EQ(sim.counters().respawns, 0);
  for (double age : sim.agents().age) EXPECT_NEAR(age, 3.0, 1e-9);
}

TEST(ReferenceAgentSimulation, WithoutTurnoverNoRespawnsAndNoDepositBeforeActivationForwardEuler) {
  expect_newborn_start_without_turnover(Integrator::Forward);
}
TEST(ReferenceAgentSimulation, WithoutTurnoverNoRespawnsAndNoDepositBeforeActivationBackwardEuler) {
  expect_newborn_start_without_turnover(Integrator::Backward);
}

}  // namespace
}  // namespace physarum
