// The controls of paper Sec. 3.3 (common/model/simulation_controls.hpp) on both backends: read- and
// write-stimuli, spawn weights, sinks, directional bias with spawn headings, a terminating boundary
// and parameter maps read at the agent's position. Each check compares against a value derived
// independently of the code (an analytic steady state, a conservation law, an exact density, a
// counting identity), and the planted faults of the harness that concern controls are shown to fail
// the check they belong to.
#include "common/setup/agent_inputs.hpp"
#include "common/model/directional_bias.hpp"
#include "common/base/errors.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/model/simulation_controls.hpp"
#include "common/model/spawn_distribution.hpp"
#include "opencl/planted_faults.hpp"
#include "opencl/agent_simulation.hpp"
#include "reference/agent_simulation.hpp"
#include "model_scene.hpp"

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace physarum {
namespace {

enum class Backend { Reference, OpenCL };
const char* name(Backend b) { return b == Backend::Reference ? "reference" : "opencl"; }

const opencl::ComputeContext& compute() {
  static const opencl::ComputeContext c = opencl::make_compute_context("");
  return c;
}

// A surface with the 3D positions of its intrinsic vertices (flips only, so on a flat square every
// intrinsic face is a flat triangle of the plane).
struct TestSurface {
  SurfaceDomain domain;
  std::vector<Eigen::Vector3d> position;  // per intrinsic vertex
};

TestSurface make_surface(const std::string& spec) {
  SurfaceSpec s;
  s.mesh = spec;
  PreparedSurface surface = prepare_surface(s);
  TestSurface t;
  t.domain = std::move(surface.domain);
  for (int v = 0; v < t.domain.vertex_count; ++v) {
    const SurfacePoint& p = t.domain.vertex_location[v];
    const std::array<int, 3>& tri = surface.simulated.triangles[static_cast<size_t>(p.face)];
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) x += p.barycentric[k] * surface.simulated.positions[static_cast<size_t>(tri[k])];
    t.position.push_back(x);
  }
  return t;
}

const TestSurface& sphere() {
  static const TestSurface s = make_surface("shape:sphere");
  return s;
}
const TestSurface& square() {
  static const TestSurface s = make_surface("shape:square");
  return s;
}

std::unique_ptr<SimulationBackend> make(Backend b, const SurfaceDomain& domain, const VertexParameters& params,
                                        const SimulationControls& controls, const SimulationSettings& settings,
                                        const std::string& fault = "") {
  if (b == Backend::Reference) return std::make_unique<ReferenceAgentSimulation>(domain, params, controls, settings);
  opencl::OpenCLBackendOptions options;
  options.build_options = opencl::fault_build_option(fault);
  return std::make_unique<opencl::OpenCLAgentSimulation>(compute(), domain, params, controls, settings, options);
}

Agents agents_of(const SimulationBackend& sim) {
  if (const auto* r = dynamic_cast<const ReferenceAgentSimulation*>(&sim)) return r->agents();
  return dynamic_cast<const opencl::OpenCLAgentSimulation&>(sim).read_agents();
}

SimulationSettings settings_of(const Scene& scene) { return simulation_settings(scene); }

// ---- default controls ----

// Default controls are the base model: the constructor without controls delegates, and a zero write
// rate (present, so its extra pass runs) adds exactly 0 to a non-negative field, bit for bit.
void expect_zero_write_rate_changes_nothing(Backend b, Integrator integrator) {
  const Scene scene = testing::model_scene(500, 0.01, 0.2, integrator);
  const SurfaceDomain& d = sphere().domain;
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, d.vertex_count);
  SimulationControls zero;
  zero.write_rate.assign(static_cast<size_t>(d.vertex_count), 0.0);
  auto base = make(b, d, params, SimulationControls{}, settings_of(scene));
  auto with = make(b, d, params, zero, settings_of(scene));
  base->run(20);
  with->run(20);
  const IntrinsicVertexData<double> u0 = base->field_values(), u1 = with->field_values();
  ASSERT_EQ(u0.size(), u1.size());
  for (size_t i = 0; i < u0.size(); ++i) ASSERT_EQ(u0[i], u1[i]) << name(b) << " vertex " << i;
  EXPECT_EQ(base->agent_faces(), with->agent_faces()) << name(b);
}

TEST(Controls, ZeroWriteRateIsBitIdenticalToNone) {
  for (Backend b : {Backend::Reference, Backend::OpenCL})
    for (Integrator i : {Integrator::Forward, Integrator::Backward}) expect_zero_write_rate_changes_nothing(b, i);
}

// ---- write-stimuli: the source term ----

// No agents, no diffusion: du/dt = w - r_dec u has the steady state w / r_dec (0 where w < 0, the
// concentration being clamped at zero), exactly for both integrators' fixed points.
void expect_write_steady_state(Backend b, Integrator integrator) {
  Scene scene = testing::model_scene(0, 0.05, std::nullopt, integrator);
  scene.agent_model().parameters[Param::diffuse_rate] = 0.0;
  const double r_dec = scene.agent_model().parameters[Param::decay_rate];
  const SurfaceDomain& d = sphere().domain;
  SimulationControls controls;
  controls.write_rate.assign(static_cast<size_t>(d.vertex_count), 0.0);
  for (int i = 0; i < d.vertex_count; ++i) controls.write_rate[i] = -0.5 + 2.5 * ((i * 37) % 101) / 100.0;
  auto sim = make(b, d, VertexParameters::constant(scene.agent_model().parameters, d.vertex_count), controls, settings_of(scene));
  sim->run(600);  // 30 s = 75 relaxation times 1 / r_dec: the transient is below 1e-30
  const IntrinsicVertexData<double> u = sim->field_values();
  for (int i = 0; i < d.vertex_count; ++i) {
    const double expected = std::max(controls.write_rate[i], 0.0) / r_dec;
    ASSERT_NEAR(u[i], expected, 1e-6 * std::max(1.0, expected)) << name(b) << " vertex " << i;
  }
}

TEST(Controls, WriteStimulusReachesRateOverDecay) {
  for (Backend b : {Backend::Reference, Backend::OpenCL})
    for (Integrator i : {Integrator::Forward, Integrator::Backward}) expect_write_steady_state(b, i);
}

// ---- the U metric under maps and controls ----

// With uniform deposit, decay and lifetime, the total deposit per second is N r_dep times the
// active fraction exp(-t_a / tau) wherever the agents go, so the mass-weighted mean of the field
// relaxes to U (Eq. 5) whatever maps steer them: here sensor distance and move rate vary 4x across
// the sphere and a read-stimulus and a bias act too. Time-averaged over 2 s after 3 s (7.5 decay
// times) of relaxation.
void expect_u_metric(Backend b) {
  Scene scene = testing::model_scene(3000, 0.01, 1.0, Integrator::Forward);
  scene.agent_model().parameters[Param::activation_time] = 0.02;
  const TestSurface& s = sphere();
  const SurfaceDomain& d = s.domain;
  VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, d.vertex_count);
  SimulationControls controls;
  controls.read_stimulus.assign(static_cast<size_t>(d.vertex_count), 0.0);
  DirectionalBias bias;
  bias.symmetry = 2;
  bias.strength.assign(static_cast<size_t>(d.vertex_count), 1.0);
  bias.direction.assign(static_cast<size_t>(d.face_count), {1.0, 0.0});
  controls.bias = bias;
  for (int i = 0; i < d.vertex_count; ++i) {
    const double ramp = 0.5 * (s.position[static_cast<size_t>(i)].z() / s.position[static_cast<size_t>(i)].norm() + 1.0);
    params[Param::sensor_distance][i] *= 0.5 + 1.5 * ramp;
    params[Param::move_rate][i] *= 2.0 - 1.5 * ramp;
    controls.read_stimulus[i] = 0.3 * ramp;
  }
  const double U = uniform_steady_state(scene, d.total_area);
  auto sim = make(b, d, params, controls, settings_of(scene));
  sim->run(300);
  double sum = 0.0;
  const int samples = 40;
  for (int k = 0; k < samples; ++k) {
    sim->run(5);
    sum += sim->field_statistics(U).mean;
  }
  EXPECT_NEAR(sum / samples / U, 1.0, 0.01) << name(b);
}

TEST(Controls, UMetricHoldsWithParameterMapsAndControls) {
  for (Backend b : {Backend::Reference, Backend::OpenCL}) expect_u_metric(b);
}

// ---- spawn weights ----

// The in-face sampler against the exact linear density w.b: the four midpoint sub-triangles hold
// probability (area 1/4) x (weight at their centroid) / (mean weight) (exact for a linear density),
// tested by chi-square at the 0.1 % level, and the mean barycentric coordinate is (w_j + W) / (4 W)
// (integrals of b_i b_j over a triangle).
TEST(Controls, LinearDensityInFaceIsExact) {
  const Eigen::Vector3d w(1.0, 0.0, 3.0);
  const double W = w.sum();
  const auto value = [&](const Eigen::Vector3d& b) { return w.dot(b); };
  const std::array<Eigen::Vector3d, 4> centroid = {Eigen::Vector3d(2, 0.5, 0.5) / 3.0, Eigen::Vector3d(0.5, 2, 0.5) / 3.0,
                                                   Eigen::Vector3d(0.5, 0.5, 2) / 3.0, Eigen::Vector3d(1, 1, 1) / 3.0};
  const int n = 200000;
  std::array<int, 4> count{};
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const PhiloxWords r1 = random_words(3, static_cast<std::uint32_t>(k), 0, 90, 0);
    const PhiloxWords r2 = random_words(3, static_cast<std::uint32_t>(k), 0, 91, 0);
    const Eigen::Vector3d b = linear_density_barycentric(w, first_uniform(r1), second_uniform(r1), first_uniform(r2));
    ASSERT_NEAR(b.sum(), 1.0, 1e-12);
    ASSERT_GE(b.minCoeff(), 0.0);
    mean += b / n;
    // Corner sub-triangle i is where b_i > 1/2; the middle one where every b_i < 1/2.
    int region = 3;
    for (int i = 0; i < 3; ++i)
      if (b[i] > 0.5) region = i;
    ++count[static_cast<size_t>(region)];
  }
  double chi2 = 0.0;
  for (int r = 0; r < 4; ++r) {
    const double expected = n * 0.25 * value(centroid[static_cast<size_t>(r)]) / (W / 3.0);
    chi2 += std::pow(count[static_cast<size_t>(r)] - expected, 2) / expected;
  }
  const boost::math::chi_squared_distribution<double> dist(3);
  EXPECT_LT(chi2, boost::math::quantile(boost::math::complement(dist, 0.001)));
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(mean[j], (w[j] + W) / (4.0 * W), 0.003) << "coordinate " << j;
}

// Spawn weights on the sphere: zero on a cap (vertices with z > 0.4 r), a ramp elsewhere.
IntrinsicVertexData<double> cap_and_ramp_weights(const TestSurface& s) {
  IntrinsicVertexData<double> w(s.position.size());
  for (size_t i = 0; i < s.position.size(); ++i) {
    const double z = s.position[i].z() / s.position[i].norm();
    w[i] = z > 0.4 ? 0.0 : 1.0 + 2.0 * (1.0 - z);
  }
  return w;
}

// Where the initial agents stand against area x mean corner weight, over ten height bands of faces
// (chi-square at the 0.1 % level), and no agent on a face whose three corners weigh zero, after
// the initial placement and after many respawns (short lifetime). The fault spawn-weights-ignored
// is caught by the zero-weight check.
void expect_spawn_density(Backend b, const std::string& fault = "") {
  const TestSurface& s = sphere();
  const SurfaceDomain& d = s.domain;
  Scene scene = testing::model_scene(20000, 0.01, 0.02, Integrator::Forward);
  SimulationControls controls;
  controls.spawn_weight = cap_and_ramp_weights(s);
  auto sim = make(b, d, VertexParameters::constant(scene.agent_model().parameters, d.vertex_count), controls, settings_of(scene), fault);
  const auto zero_face = [&](int f) {
    for (int v : d.face_vertices[f])
      if (controls.spawn_weight[v] != 0.0) return false;
    return true;
  };
  // Groups of faces: ten bands of height on the sphere (the weights vary with height), so a sampler
  // that got the weights wrong moves agents between groups.
  const int groups = 10;
  const auto group_of = [&](int f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : d.face_vertices[f]) c += s.position[static_cast<size_t>(v)] / 3.0;
    return std::clamp(static_cast<int>((c.z() / c.norm() + 1.0) / 2.0 * groups), 0, groups - 1);
  };
  int in_zero = 0;
  std::vector<double> observed(groups, 0.0), expected(groups, 0.0);
  for (int f : sim->agent_faces()) {
    in_zero += zero_face(f) ? 1 : 0;
    observed[static_cast<size_t>(group_of(f))] += 1.0;
  }
  if (!fault.empty()) {
    EXPECT_GT(in_zero, 0) << "the planted fault " << fault << " went unnoticed";
    return;
  }
  EXPECT_EQ(in_zero, 0) << name(b) << ": agents placed where every corner weighs zero";
  double total = 0.0;
  for (int f = 0; f < d.face_count; ++f) {
    double mean_weight = 0.0;
    for (int v : d.face_vertices[f]) mean_weight += controls.spawn_weight[v] / 3.0;
    expected[static_cast<size_t>(group_of(f))] += d.face_area[f] * mean_weight;
    total += d.face_area[f] * mean_weight;
  }
  double chi2 = 0.0;
  int used = 0;
  for (int g = 0; g < groups; ++g) {
    const double e = expected[static_cast<size_t>(g)] / total * scene.agent_model().agents;
    if (e == 0.0) continue;  // a band inside the zero cap: covered by the check above
    chi2 += std::pow(observed[static_cast<size_t>(g)] - e, 2) / e;
    ++used;
  }
  const boost::math::chi_squared_distribution<double> dist(used - 1);
  EXPECT_LT(chi2, boost::math::quantile(boost::math::complement(dist, 0.001))) << name(b);
  // 30 steps of a 0.02 s lifetime at dt 0.01: every agent respawns several times. Agents walk into
  // the zero region freely; the newborns of a step (age 0 at its end) never stand there.
  for (int step = 0; step < 30; ++step) {
    sim->step();
    const Agents a = agents_of(*sim);
    for (int i = 0; i < a.count(); ++i)
      if (a.age[i] == 0.0) {
        ASSERT_FALSE(zero_face(a.face[i])) << name(b) << ": a respawn landed on a zero-weight face";
      }
  }
  EXPECT_GT(sim->counters().respawns, 2 * scene.agent_model().agents) << name(b);
}

TEST(Controls, SpawnPositionsFollowAreaTimesWeight) {
  for (Backend b : {Backend::Reference, Backend::OpenCL}) expect_spawn_density(b);
}

TEST(Controls, PlantedFaultSpawnWeightsIgnoredIsCaught) {
  expect_spawn_density(Backend::OpenCL, "spawn-weights-ignored");
}

TEST(Controls, AllZeroSpawnWeightsAreRefused) {
  const SurfaceDomain& d = sphere().domain;
  const Scene scene = testing::model_scene(10, 0.01, 0.2, Integrator::Forward);
  SimulationControls controls;
  controls.spawn_weight.assign(static_cast<size_t>(d.vertex_count), 0.0);
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, d.vertex_count);
  for (Backend b : {Backend::Reference, Backend::OpenCL})
    EXPECT_THROW(make(b, d, params, controls, settings_of(scene)), InputError) << name(b);
  controls.spawn_weight[0] = -1.0;
  EXPECT_THROW(make(Backend::Reference, d, params, controls, settings_of(scene)), InputError);
}

// ---- sinks ----

// Mean lifetime 0 on a cap: agents that enter a face touching it are removed and respawned in the
// same step, and no respawn lands there, so after every step no agent stands on such a face.
void expect_sink_empty(Backend b) {
  const TestSurface& s = sphere();
  const SurfaceDomain& d = s.domain;
  Scene scene = testing::model_scene(3000, 0.01, std::nullopt, Integrator::Forward);
  VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, d.vertex_count);
  std::vector<char> sink(static_cast<size_t>(d.vertex_count), 0);
  for (int i = 0; i < d.vertex_count; ++i)
    if (s.position[static_cast<size_t>(i)].z() / s.position[static_cast<size_t>(i)].norm() > 0.5) {
      params[Param::mean_lifetime][i] = 0.0;
      sink[static_cast<size_t>(i)] = 1;
    }
  auto sim = make(b, d, params, SimulationControls{}, settings_of(scene));
  for (int step = 0; step <= 60; ++step) {
    for (int f : sim->agent_faces())
      for (int v : d.face_vertices[f]) ASSERT_FALSE(sink[static_cast<size_t>(v)]) << name(b) << " after step " << step;
    sim->step();
  }
  // No turnover outside the sink: every respawn is an agent that walked into it.
  EXPECT_GT(sim->counters().respawns, 0) << name(b);
}

TEST(Controls, SinkRegionHoldsNoAgentAfterAnyStep) {
  for (Backend b : {Backend::Reference, Backend::OpenCL}) expect_sink_empty(b);
}

// ---- directional bias ----

// The bias rule itself: the closest of n copies, and exact exponential relaxation.
TEST(Controls, BiasTurnsTowardTheClosestCopyExactly) {
  const Eigen::Vector2d east(1.0, 0.0);
  const auto at = [](double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    return Eigen::Vector2d(std::cos(a), std::sin(a));
  };
  EXPECT_NEAR(angle_from_closest_copy(at(30), east, 1), 30 * std::numbers::pi / 180, 1e-12);
  EXPECT_NEAR(angle_from_closest_copy(at(170), east, 2), -10 * std::numbers::pi / 180, 1e-12);  // copy at 180
  EXPECT_NEAR(angle_from_closest_copy(at(100), east, 4), 10 * std::numbers::pi / 180, 1e-12);   // copy at 90
  // d(delta)/dt = -s delta over dt: delta (1 - exp(-s dt)) of turn, toward the copy.
  EXPECT_NEAR(bias_turn(at(30), east, 2.0, 1, 0.5), -(30 * std::numbers::pi / 180) * (1 - std::exp(-1.0)), 1e-12);
  EXPECT_EQ(bias_turn(at(30), Eigen::Vector2d::Zero(), 2.0, 1, 0.5), 0.0);
}

// The world x axis in each face's own frame, on a flat surface in the xy plane.
std::vector<std::array<double, 2>> world_x_in_faces(const TestSurface& s) {
  const SurfaceDomain& d = s.domain;
  std::vector<std::array<double, 2>> out(static_cast<size_t>(d.face_count));
  for (int f = 0; f < d.face_count; ++f) {
    const std::array<int, 3>& v = d.face_vertices[f];
    const Eigen::Vector3d e1 = s.position[static_cast<size_t>(v[1])] - s.position[static_cast<size_t>(v[0])];
    const Eigen::Vector3d e2 = s.position[static_cast<size_t>(v[2])] - s.position[static_cast<size_t>(v[0])];
    // x = alpha e1 + beta e2 in the plane, then the same combination of the frame's corners.
    Eigen::Matrix2d m;
    m << e1.x(), e2.x(), e1.y(), e2.y();
    const Eigen::Vector2d ab = m.inverse() * Eigen::Vector2d(1.0, 0.0);
    const Eigen::Vector2d x = ab[0] * d.face_corners[f][1] + ab[1] * d.face_corners[f][2];
    out[static_cast<size_t>(f)] = {x.x(), x.y()};
  }
  return out;
}

// mean over agents of cos(n (theta - theta_bias)), in each agent's face frame.
double heading_alignment(const SimulationBackend& sim, const DirectionalBias& bias) {
  const Agents a = agents_of(sim);
  double sum = 0.0;
  for (int i = 0; i < a.count(); ++i) {
    const std::array<double, 2>& d = bias.direction[static_cast<size_t>(a.face[i])];
    sum += std::cos(bias.symmetry * angle_from_closest_copy(a.heading[i], Eigen::Vector2d(d[0], d[1]), bias.symmetry));
  }
  return sum / a.count();
}

// On shape:square with a uniform direction (world x): without bias the headings are isotropic
// (alignment within 0.08 of 0); with strength 20 rad/s the alignment after 1 s rises above 0.8 for
// n = 2 and 4 (measured 0.986 and 0.946 on both backends) and above 0.35 for n = 1 (measured 0.45):
// with one copy the agents pile up against the east wall, where every reflection points them
// backwards until the bias turns them round (a stronger bias makes that worse: 0.08 at 200 rad/s).
// The fault bias-farthest-copy drives headings away from every copy, alignment below 0; for n = 1
// the farthest copy is the closest, so only n = 2 and 4 can show it.
double alignment_after(Backend b, int symmetry, double strength, const std::string& fault = "") {
  const TestSurface& s = square();
  const SurfaceDomain& d = s.domain;
  const Scene scene = testing::model_scene(2000, 0.01, std::nullopt, Integrator::Forward);
  SimulationControls controls;
  DirectionalBias bias;
  bias.symmetry = symmetry;
  bias.direction = IntrinsicFaceData<std::array<double, 2>>(world_x_in_faces(s));
  bias.strength.assign(static_cast<size_t>(d.vertex_count), strength);
  controls.bias = bias;
  auto sim = make(b, d, VertexParameters::constant(scene.agent_model().parameters, d.vertex_count), controls, settings_of(scene), fault);
  sim->run(100);
  return heading_alignment(*sim, bias);
}

TEST(Controls, BiasConcentratesHeadingsOnTheCopies) {
  for (Backend b : {Backend::Reference, Backend::OpenCL})
    for (int n : {1, 2, 4}) {
      EXPECT_NEAR(alignment_after(b, n, 0.0), 0.0, 0.08) << name(b) << " n=" << n << " without bias";
      EXPECT_GT(alignment_after(b, n, 20.0), n == 1 ? 0.35 : 0.8) << name(b) << " n=" << n;
    }
}

TEST(Controls, PlantedFaultBiasFarthestCopyIsCaught) {
  for (int n : {2, 4}) EXPECT_LT(alignment_after(Backend::OpenCL, n, 20.0, "bias-farthest-copy"), 0.0) << "n=" << n;
}

// Spawn headings along the bias: every initial agent faces one of the copies exactly.
TEST(Controls, SpawnHeadingAlongBias) {
  const TestSurface& s = square();
  const SurfaceDomain& d = s.domain;
  const Scene scene = testing::model_scene(500, 0.01, 0.2, Integrator::Forward);
  SimulationControls controls;
  DirectionalBias bias;
  bias.symmetry = 3;
  bias.direction = IntrinsicFaceData<std::array<double, 2>>(world_x_in_faces(s));
  bias.strength.assign(static_cast<size_t>(d.vertex_count), 0.0);
  controls.bias = bias;
  controls.spawn_heading = SpawnHeading::Bias;
  for (Backend b : {Backend::Reference, Backend::OpenCL}) {
    auto sim = make(b, d, VertexParameters::constant(scene.agent_model().parameters, d.vertex_count), controls, settings_of(scene));
    EXPECT_NEAR(heading_alignment(*sim, bias), 1.0, 1e-5) << name(b);
  }
}

// ---- read-stimuli ----

// A disk of radius 0.25 side at the centre of the square with stimulus w: w = +2U attracts the
// agents, so the time-averaged concentration inside the disk is above 1.15x that outside (measured
// 1.27 reference, 1.28 OpenCL; a constant stimulus has no gradient inside the disk, so only its rim
// steers, and stronger weights saturate: 1.31 at 20U); w = -2U repels them, below 0.8x (measured
// 0.62 reference, 0.63 OpenCL). The fault
// stimulus-sign (w negated) turns attraction into repulsion and is caught by the first bound.
double disk_ratio(Backend b, double weight_in_u, const std::string& fault = "") {
  const TestSurface& s = square();
  const SurfaceDomain& d = s.domain;
  const Scene scene = testing::model_scene(3000, 0.01, 1.0, Integrator::Forward);
  const double U = uniform_steady_state(scene, d.total_area);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : s.position) centre += p / static_cast<double>(s.position.size());
  const double radius = 0.25 * std::sqrt(d.total_area);
  SimulationControls controls;
  controls.read_stimulus.assign(static_cast<size_t>(d.vertex_count), 0.0);
  std::vector<char> inside(static_cast<size_t>(d.vertex_count), 0);
  for (int i = 0; i < d.vertex_count; ++i)
    if ((s.position[static_cast<size_t>(i)] - centre).norm() < radius) {
      inside[static_cast<size_t>(i)] = 1;
      controls.read_stimulus[i] = weight_in_u * U;
    }
  auto sim = make(b, d, VertexParameters::constant(scene.agent_model().parameters, d.vertex_count), controls, settings_of(scene), fault);
  sim->run(100);
  double in = 0.0, out = 0.0, m_in = 0.0, m_out = 0.0;
  for (int k = 0; k < 20; ++k) {
    sim->run(10);
    const IntrinsicVertexData<double> u = sim->field_values();
    for (int i = 0; i < d.vertex_count; ++i) {
      const double m = d.vertex_mass[i];
      (inside[static_cast<size_t>(i)] ? in : out) += m * u[i];
      (inside[static_cast<size_t>(i)] ? m_in : m_out) += m;
    }
  }
  return (in / m_in) / (out / m_out);
}

TEST(Controls, ReadStimulusAttractsAndRepels) {
  for (Backend b : {Backend::Reference, Backend::OpenCL}) {
    EXPECT_GT(disk_ratio(b, 2.0), 1.15) << name(b);
    EXPECT_LT(disk_ratio(b, -2.0), 0.8) << name(b);
  }
}

TEST(Controls, PlantedFaultStimulusSignIsCaught) { EXPECT_LT(disk_ratio(Backend::OpenCL, 2.0, "stimulus-sign"), 1.15); }

// ---- spatially varying lifetime: the initial state ----

// Mean lifetime 0.1 s on the northern cap, 1 s on the southern one: the initial agents already hold
// the steady-state age distribution of the place they stand, Exp(tau_local), so their mean age on
// faces entirely inside each cap is tau_local (within 5 %: ~6000 agents a cap, sd ~1.3 %), and the
// depositing fraction exp(-t_a / tau) holds from step 0 (no inspection-paradox bias).
TEST(Controls, InitialAgesFollowTheLocalLifetime) {
  const TestSurface& s = sphere();
  const SurfaceDomain& d = s.domain;
  const Scene scene = testing::model_scene(20000, 0.01, 1.0, Integrator::Forward);
  VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, d.vertex_count);
  std::vector<int> cap(static_cast<size_t>(d.vertex_count));
  for (int i = 0; i < d.vertex_count; ++i) {
    const double z = s.position[static_cast<size_t>(i)].z() / s.position[static_cast<size_t>(i)].norm();
    cap[static_cast<size_t>(i)] = z > 0.3 ? 1 : (z < -0.3 ? 2 : 0);
    params[Param::mean_lifetime][i] = z > 0.0 ? 0.1 : 1.0;
  }
  for (Backend b : {Backend::Reference, Backend::OpenCL}) {
    auto sim = make(b, d, params, SimulationControls{}, settings_of(scene));
    const Agents a = agents_of(*sim);
    std::array<double, 3> sum{}, count{};
    for (int i = 0; i < a.count(); ++i) {
      const std::array<int, 3>& v = d.face_vertices[a.face[i]];
      const int c = cap[static_cast<size_t>(v[0])];
      if (c == 0 || cap[static_cast<size_t>(v[1])] != c || cap[static_cast<size_t>(v[2])] != c) continue;
      sum[static_cast<size_t>(c)] += a.age[i];
      count[static_cast<size_t>(c)] += 1.0;
    }
    ASSERT_GT(count[1], 3000) << name(b);
    ASSERT_GT(count[2], 3000) << name(b);
    EXPECT_NEAR(sum[1] / count[1], 0.1, 0.005) << name(b) << " northern cap";
    EXPECT_NEAR(sum[2] / count[2], 1.0, 0.05) << name(b) << " southern cap";
  }
}

// ---- terminating boundary ----

// With no turnover, every respawn is a termination, and every move that meets the boundary
// terminates: respawns == boundary hits, and both are many on a square. With the default (reflect)
// there is no respawn at all.
TEST(Controls, TerminateRespawnsAtTheBoundary) {
  const SurfaceDomain& d = square().domain;
  const Scene scene = testing::model_scene(2000, 0.01, std::nullopt, Integrator::Forward);
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, d.vertex_count);
  SimulationControls terminate;
  terminate.boundary = BoundaryBehaviour::Terminate;
  for (Backend b : {Backend::Reference, Backend::OpenCL}) {
    auto sim = make(b, d, params, terminate, settings_of(scene));
    sim->run(100);
    const SimulationCounters c = sim->counters();
    EXPECT_GT(c.boundary_hits, 100) << name(b);
    EXPECT_EQ(c.respawns, c.boundary_hits) << name(b);
    auto reflect = make(b, d, params, SimulationControls{}, settings_of(scene));
    reflect->run(100);
    EXPECT_GT(reflect->counters().boundary_hits, 100) << name(b);
    EXPECT_EQ(reflect->counters().respawns, 0) << name(b);
  }
}

// ---- parameter maps at the agent's position ----

// The move rate is a map; agents placed near corner 0 of their face, heading to the face's
// interior, walk one step of length v(x) dt with v interpolated at their start. The fault
// map-at-centroid reads v at the centroid instead and is caught.
double worst_move_error(Backend b, const std::string& fault = "") {
  const SurfaceDomain& d = sphere().domain;
  Scene scene = testing::model_scene(64, 0.001, std::nullopt, Integrator::Forward);
  VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, d.vertex_count);
  for (int i = 0; i < d.vertex_count; ++i) params[Param::move_rate][i] = 0.5 + (i % 7) * 0.5;
  params[Param::turn_frequency].assign(static_cast<size_t>(d.vertex_count), 1e-3);  // no turn decision in one step
  auto sim = make(b, d, params, SimulationControls{}, settings_of(scene), fault);
  Agents a = agents_of(*sim);
  std::vector<double> expected(static_cast<size_t>(a.count()));
  for (int i = 0; i < a.count(); ++i) {
    const int f = (i * 13) % d.face_count;
    const auto& c = d.face_corners[f];
    a.face[i] = f;
    a.position[i] = 0.8 * c[0] + 0.1 * c[1] + 0.1 * c[2];
    a.heading[i] = (((c[1] + c[2]) / 2.0) - a.position[i]).normalized();  // toward the far edge's midpoint
    a.time_since_decision[i] = 0.0;
    const std::array<int, 3>& v = d.face_vertices[f];
    expected[static_cast<size_t>(i)] = scene.time_step * (0.8 * params[Param::move_rate][v[0]] +
                                                          0.1 * params[Param::move_rate][v[1]] +
                                                          0.1 * params[Param::move_rate][v[2]]);
  }
  if (auto* r = dynamic_cast<ReferenceAgentSimulation*>(sim.get())) r->agents() = a;
  else dynamic_cast<opencl::OpenCLAgentSimulation&>(*sim).write_agents(a);
  sim->step();
  const Agents moved = agents_of(*sim);
  double worst = 0.0;
  for (int i = 0; i < a.count(); ++i) {
    EXPECT_EQ(moved.face[i], a.face[i]) << name(b) << ": a step this short stays in its face";
    const double walked = (moved.position[i] - a.position[i]).norm();
    worst = std::max(worst, std::abs(walked - expected[static_cast<size_t>(i)]) / expected[static_cast<size_t>(i)]);
  }
  return worst;
}

TEST(Controls, AgentParametersAreInterpolatedAtThePosition) {
  EXPECT_LT(worst_move_error(Backend::Reference), 1e-9);
  EXPECT_LT(worst_move_error(Backend::OpenCL), 1e-3);
}

TEST(Controls, PlantedFaultMapAtCentroidIsCaught) { EXPECT_GT(worst_move_error(Backend::OpenCL, "map-at-centroid"), 0.05); }

}  // namespace
}  // namespace physarum
