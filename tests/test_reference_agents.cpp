// The agent model of the serial reference, piece by piece: random streams, spawning, turnover and
// the steady-state initial ages, Jones' steering rule at a fixed decision frequency, sensors at
// boundaries, movement (reflection, geodesics) and deposition along the path (Eq. 4).
//
// Statistical checks use fixed seeds (so they are deterministic) and state their significance
// level; each was verified to fail on a deliberately broken implementation.
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/base/random_streams.hpp"
#include "common/scene/default_scene.hpp"
#include "common/scene/scene.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/surface/trace.hpp"
#include "common/model/vertex_parameters.hpp"
#include "reference/agents.hpp"
#include "reference/deposition.hpp"
#include "reference/movement.hpp"
#include "reference/sensing_steering.hpp"
#include "reference/agent_simulation.hpp"
#include "reference/turnover.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace physarum {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

// Chi-square critical values at significance 0.001 (upper tail), by degrees of freedom.
double chi_square_critical_0001(int dof) {
  static const double table[] = {0, 10.828, 13.816, 16.266, 18.467, 20.515, 22.458, 24.322, 26.124, 27.877, 29.588};
  return table[dof];
}

// A flat strip of six triangles with areas 0.5, 0.5, 1, 1, 1.5, 1.5 (distinct weights for the
// area-weighted face choice).
InputMesh uneven_strip() {
  InputMesh m;
  m.source = "uneven strip";
  const double xs[] = {0.0, 1.0, 3.0, 6.0};
  for (double x : xs) m.positions.emplace_back(x, 0.0, 0.0);
  for (double x : xs) m.positions.emplace_back(x, 1.0, 0.0);
  for (int i = 0; i < 3; ++i) {
    m.triangles.push_back({i, i + 1, i + 5});
    m.triangles.push_back({i, i + 5, i + 4});
  }
  for (int i = 0; i < m.vertex_count(); ++i) m.file_vertex.push_back(i);
  return m;
}

// The domain of a mesh exactly as given (no flips), so intrinsic faces ARE the input triangles.
SurfaceDomain domain_as_is(const InputMesh& mesh) { return build_surface_domain(intrinsic_mesh_from_input(mesh)); }

// A Scene with plain values, for building parameter maps.
Scene plain_scene() {
  Scene s = default_scene_parameters(1);
  s.mesh = "shape:square";
  s.agent_model().parameters[Param::diffuse_rate] = 0.0;
  return s;
}

// 3D position of a point of a domain built by domain_as_is from `mesh`.
Eigen::Vector3d point_in_3d(const InputMesh& mesh, const SurfaceDomain& domain, int face, const Eigen::Vector2d& p) {
  const Eigen::Vector3d b = barycentric_in_face(domain, face, p);
  const auto& t = mesh.triangles[face];
  return b[0] * mesh.positions[t[0]] + b[1] * mesh.positions[t[1]] + b[2] * mesh.positions[t[2]];
}

// Finds the face containing a point of the flat unit square (z = 0) and its position in that
// face's frame (the square's domain is built as-is, so frames are rigid copies of the triangles).
FacePoint locate_on_flat(const InputMesh& mesh, const SurfaceDomain& domain, const Eigen::Vector2d& xy) {
  for (int f = 0; f < domain.face_count; ++f) {
    const auto& t = mesh.triangles[f];
    const Eigen::Vector2d a = mesh.positions[t[0]].head<2>(), b = mesh.positions[t[1]].head<2>(),
                          c = mesh.positions[t[2]].head<2>();
    Eigen::Matrix2d m;
    m << b - a, c - a;
    const Eigen::Vector2d w = m.inverse() * (xy - a);
    if (w.x() >= -1e-12 && w.y() >= -1e-12 && w.x() + w.y() <= 1 + 1e-12) {
      const auto& k = domain.face_corners[f];
      return {f, (1 - w.x() - w.y()) * k[0] + w.x() * k[1] + w.y() * k[2]};
    }
  }
  return {};
}

// The axes of face f's frame in 3D, for a domain built by domain_as_is (corner 0 at the origin,
// corner 1 on +x, corner 2 above: x along edge 01, y = normal x x).
std::pair<Eigen::Vector3d, Eigen::Vector3d> frame_axes(const InputMesh& mesh, int f) {
  const auto& t = mesh.triangles[f];
  const Eigen::Vector3d e01 = mesh.positions[t[1]] - mesh.positions[t[0]];
  const Eigen::Vector3d n = e01.cross(mesh.positions[t[2]] - mesh.positions[t[0]]).normalized();
  const Eigen::Vector3d x = e01.normalized();
  return {x, n.cross(x)};
}

// The direction in face f's frame of a 3D direction lying in the (flat) face.
Eigen::Vector2d direction_in_face(const InputMesh& mesh, int f, const Eigen::Vector3d& d) {
  const auto [x, y] = frame_axes(mesh, f);
  return Eigen::Vector2d(d.dot(x), d.dot(y)).normalized();
}

Eigen::Vector3d direction_in_3d(const InputMesh& mesh, int f, const Eigen::Vector2d& d) {
  const auto [x, y] = frame_axes(mesh, f);
  return d.x() * x + d.y() * y;
}

// Angle of a frame direction on the flat square, in the square's xy plane, degrees.
double angle_on_flat(const InputMesh& mesh, int f, const Eigen::Vector2d& heading) {
  const Eigen::Vector3d d = direction_in_3d(mesh, f, heading);
  return std::atan2(d.y(), d.x()) / kDegree;
}

// ---------------------------------------------------------------------------------------------
TEST(ReferenceAgents, RandomStreamsAreAddressedBySeedAgentStepAndPurpose) {
  const PhiloxWords a = agent_random_words(7, 3, 11, RandomPurpose::RespawnState);
  EXPECT_EQ(a, agent_random_words(7, 3, 11, RandomPurpose::RespawnState));
  EXPECT_NE(a, agent_random_words(8, 3, 11, RandomPurpose::RespawnState));
  EXPECT_NE(a, agent_random_words(7, 4, 11, RandomPurpose::RespawnState));
  EXPECT_NE(a, agent_random_words(7, 3, 12, RandomPurpose::RespawnState));
  EXPECT_NE(a, agent_random_words(7, 3, 11, RandomPurpose::RespawnPlacement));
  // The convention itself: key (seed, agent), counter (step, purpose, index, 0).
  EXPECT_EQ(a, philox4x32_10({11u, static_cast<std::uint32_t>(RandomPurpose::RespawnState), 0u, 0u}, {7u, 3u}));
}

TEST(ReferenceAgents, RespawnFacesFollowAreaWeightsAndPointsAreUniformInsideFaces) {
  const InputMesh mesh = uneven_strip();
  const SurfaceDomain domain = domain_as_is(mesh);
  ASSERT_EQ(domain.face_count, 6);
  const int draws = 60000, per_step = 100;
  Agents agents, again;
  agents.resize(per_step);
  again.resize(per_step);
  std::vector<int> count(6, 0);
  int in_corner[3] = {0, 0, 0};
  for (int i = 0; i < draws; ++i) {
    // Many agents and steps: every (agent, step) pair is its own stream.
    const int a = i % per_step;
    const auto step = static_cast<std::uint32_t>(i / per_step);
    respawn_agent(domain, 5, step, a, agents);
    respawn_agent(domain, 5, step, a, again);
    ASSERT_EQ(agents.position[a], again.position[a]);  // same stream, same draw
    const int f = agents.face[a];
    ++count[f];
    const Eigen::Vector3d b = barycentric_in_face(domain, f, agents.position[a]);
    ASSERT_GE(b.minCoeff(), -1e-12) << "respawned outside its face";
    for (int k = 0; k < 3; ++k) in_corner[k] += b[k] > 0.5;  // the corner triangle holds 1/4 of the area
    ASSERT_EQ(agents.age[a], 0.0);
    ASSERT_EQ(agents.exposure[a], 0.0);
    ASSERT_GT(agents.exposure_threshold[a], 0.0);
  }
  double chi2 = 0.0;
  for (int f = 0; f < 6; ++f) {
    const double expected = draws * domain.face_area[f] / domain.total_area;
    chi2 += (count[f] - expected) * (count[f] - expected) / expected;
  }
  EXPECT_LT(chi2, chi_square_critical_0001(5)) << "face choice is not area-weighted (chi-square, 5 dof, alpha 0.001)";
  // Uniform inside a triangle: the region b_k > 1/2 is a similar triangle of 1/4 of the area.
  const double se = std::sqrt(0.25 * 0.75 / draws);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(in_corner[k] / double(draws), 0.25, 4 * se) << "corner " << k;
}

TEST(ReferenceAgents, LifetimesAreExponentialWithTheMeanLifetime) {
  // Newborn agents, constant mean lifetime tau: each lives K steps with P(K > k) = exp(-k dt / tau),
  // i.e. an Exp(tau) lifetime observed at step resolution. Chi-square over 10 bins whose edges are
  // the steps nearest the deciles of Exp(tau); alpha 0.001.
  const SurfaceDomain domain = domain_as_is(uneven_strip());
  const double tau = 0.5, dt = 0.01;
  const int n = 20000;
  const IntrinsicVertexData<double> hazard(static_cast<size_t>(domain.vertex_count), 1.0 / tau);
  Agents agents;
  agents.resize(n);
  for (int a = 0; a < n; ++a) respawn_agent(domain, 9, 0, a, agents);
  std::vector<long long> first_death(n, -1);
  int alive = n;
  for (std::uint32_t step = 1; alive > 0 && step < 100000; ++step) {
    advance_turnover(domain, hazard, dt, 9, step, agents);
    for (int a = 0; a < n; ++a)
      if (first_death[a] < 0 && agents.age[a] == 0.0) {
        first_death[a] = step;
        --alive;
      }
  }
  ASSERT_EQ(alive, 0);
  const double q = std::exp(-dt / tau);
  std::vector<long long> edges = {0};
  for (int j = 1; j < 10; ++j) edges.push_back(std::llround(-tau * std::log(1.0 - j / 10.0) / dt));
  std::vector<int> observed(10, 0);
  double sum = 0.0;
  for (long long k : first_death) {
    sum += k * dt;
    int bin = 9;
    for (int j = 1; j < 10; ++j)
      if (k <= edges[j]) {
        bin = j - 1;
        break;
      }
    ++observed[bin];
  }
  double chi2 = 0.0;
  for (int j = 0; j < 10; ++j) {
    const double p = std::pow(q, double(edges[j])) - (j < 9 ? std::pow(q, double(edges[j + 1])) : 0.0);
    const double expected = n * p;
    chi2 += (observed[j] - expected) * (observed[j] - expected) / expected;
  }
  EXPECT_LT(chi2, chi_square_critical_0001(9)) << "lifetimes are not exponential (chi-square, 9 dof, alpha 0.001)";
  // Mean of K dt is dt / (1 - q) = tau + dt/2 + O(dt^2); standard error tau / sqrt(n).
  EXPECT_NEAR(sum / n, dt / (1.0 - q), 4.0 * tau / std::sqrt(double(n)));
}

TEST(ReferenceAgents, InitialAgesAreTheSteadyStateWithoutInspectionBias) {
  // Memorylessness: an agent seen at a random moment has elapsed exposure Exp(1) and remaining
  // exposure Exp(1), independent. A biased start (threshold Exp(1) with the exposure somewhere below
  // it, or everyone newborn) shows up in the mean exposure, the mean remaining exposure and the
  // fraction of agents already active.
  const SurfaceDomain domain = domain_as_is(uneven_strip());
  const double tau = 0.5, t_a = 0.2;
  const int n = 40000;
  const IntrinsicVertexData<double> hazard(static_cast<size_t>(domain.vertex_count), 1.0 / tau);
  const double frequency = 20.0, omega = 3.0;
  const IntrinsicVertexData<double> turn_frequency(hazard.size(), frequency), turn_rate(hazard.size(), omega);
  const Agents agents = initialise_agents(domain, hazard, turn_frequency, turn_rate, n, 3);
  double exposure = 0, remaining = 0, product = 0, phase = 0, phase_squared = 0;
  int active = 0;
  for (int a = 0; a < n; ++a) {
    const double r = agents.exposure_threshold[a] - agents.exposure[a];
    ASSERT_GT(r, 0.0);
    exposure += agents.exposure[a];
    remaining += r;
    product += agents.exposure[a] * r;
    active += agents.age[a] >= t_a;
    EXPECT_NEAR(agents.age[a], agents.exposure[a] * tau, 1e-12 * (1 + agents.age[a]));
    // Decision clocks: a uniform phase of the period, with the turn accumulated over it.
    const double u = agents.time_since_decision[a] * frequency;
    ASSERT_GT(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_NEAR(agents.accumulated_turn[a], omega * agents.time_since_decision[a], 1e-12);
    phase += u;
    phase_squared += u * u;
  }
  // Uniform(0, 1): mean 1/2 (sd 1/sqrt(12 n)), second moment 1/3 (sd sqrt(4/45 n)).
  EXPECT_NEAR(phase / n, 0.5, 4 / std::sqrt(12.0 * n));
  EXPECT_NEAR(phase_squared / n, 1.0 / 3.0, 4 * std::sqrt(4.0 / 45.0 / n));
  const double se = 1.0 / std::sqrt(double(n));  // Exp(1) has unit variance
  EXPECT_NEAR(exposure / n, 1.0, 4 * se);
  EXPECT_NEAR(remaining / n, 1.0, 4 * se);
  EXPECT_NEAR(product / n, 1.0, 4 * std::sqrt(3.0) * se);  // independence: E[XY] = 1, Var(XY) = 3
  const double p = std::exp(-t_a / tau);
  EXPECT_NEAR(active / double(n), p, 4 * std::sqrt(p * (1 - p) / n));

  // No turnover: newborn with an infinite threshold.
  const Agents immortal =
      initialise_agents(domain, IntrinsicVertexData<double>(hazard.size(), 0.0), turn_frequency, turn_rate, 10, 3);
  for (int a = 0; a < 10; ++a) {
    EXPECT_EQ(immortal.age[a], 0.0);
    EXPECT_TRUE(std::isinf(immortal.exposure_threshold[a]));
  }
}

TEST(ReferenceAgents, JonesRule) {
  EXPECT_EQ(jones_turn_choice({1, 2, 1}), TurnChoice::Straight);
  EXPECT_EQ(jones_turn_choice({3, 1, 2}), TurnChoice::RandomSide);
  EXPECT_EQ(jones_turn_choice({3, 2, 1}), TurnChoice::Left);
  EXPECT_EQ(jones_turn_choice({1, 2, 3}), TurnChoice::Right);
  EXPECT_EQ(jones_turn_choice({2, 2, 1}), TurnChoice::Left);   // centre ties left: not strongest
  EXPECT_EQ(jones_turn_choice({0, 0, 0}), TurnChoice::Straight);
}

// Steering on the flat square in the field u(x, y) = x: an agent heading up the y axis sees its
// right sensor (towards +x) strongest and turns right by omega / f per decision, until its centre
// sensor is strongest. Decisions come every 1/f seconds whatever dt is.
struct SteeringRun {
  double heading_angle = 0.0;  // in the square's xy plane, degrees
  int decisions = 0;
};

SteeringRun steer_in_gradient(double dt, double seconds, double sensor_angle_deg) {
  const InputMesh mesh = load_mesh("shape:square");
  const SurfaceDomain domain = domain_as_is(mesh);
  Scene scene = plain_scene();
  scene.agent_model().parameters[Param::turn_rate] = 20.0 * kDegree;  // 1 degree per decision at f = 20
  scene.agent_model().parameters[Param::turn_frequency] = 20.0;
  scene.agent_model().parameters[Param::sensor_angle] = sensor_angle_deg * kDegree;
  scene.agent_model().parameters[Param::sensor_distance] = 0.1;
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, domain.vertex_count);
  IntrinsicVertexData<double> u(static_cast<size_t>(domain.vertex_count));
  for (int v = 0; v < domain.vertex_count; ++v) u[v] = mesh.positions[v].x();
  Agents agents;
  agents.resize(1);
  const FacePoint p = locate_on_flat(mesh, domain, {0.5, 0.5});
  agents.face[0] = p.face;
  agents.position[0] = p.position;
  agents.heading[0] = direction_in_face(mesh, p.face, Eigen::Vector3d::UnitY());
  // The first whole number of steps reaching `seconds` (less than one period beyond it).
  const auto steps = static_cast<std::uint32_t>(std::ceil(seconds / dt - 1e-9));
  for (std::uint32_t s = 0; s < steps; ++s) sense_and_steer(domain, params, u, dt, 1, s, agents);
  SteeringRun r;
  r.heading_angle = angle_on_flat(mesh, agents.face[0], agents.heading[0]);
  return r;
}

TEST(ReferenceAgents, TurnsByTurnRateOverFrequencyAtFixedDecisionTimes) {
  // 20 decisions in 1 s at f = 20, each turning 1 degree to the right: 90 -> 70 degrees, for dt a
  // divisor of the period (0.01), a non-divisor (0.007) and a multiple of nothing (0.003).
  for (double dt : {0.01, 0.007, 0.003, 0.025}) {
    const double seconds = 1.0;
    EXPECT_NEAR(steer_in_gradient(dt, seconds, 22.5).heading_angle, 70.0, 1e-6) << "dt " << dt;
  }
  // Chemo-repulsion: a negative sensor angle swaps the sides, so the agent turns away (left).
  EXPECT_NEAR(steer_in_gradient(0.01, 1.0, -22.5).heading_angle, 110.0, 1e-6);
}

TEST(ReferenceAgents, CentreWeakestTurnsToARandomSide) {
  // Field u = |x - 0.5| on the square: an agent at x = 0.5 heading +y has both side sensors above the
  // centre one. Over many agents the side is a fair coin (binomial, 4.5 sigma), per agent
  // reproducible.
  const InputMesh mesh = load_mesh("shape:square");
  const SurfaceDomain domain = domain_as_is(mesh);
  Scene scene = plain_scene();
  scene.agent_model().parameters[Param::turn_rate] = 20.0 * kDegree;
  scene.agent_model().parameters[Param::sensor_distance] = 0.1;
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, domain.vertex_count);
  IntrinsicVertexData<double> u(static_cast<size_t>(domain.vertex_count));
  for (int v = 0; v < domain.vertex_count; ++v) u[v] = std::abs(mesh.positions[v].x() - 0.5);
  const int n = 4000;
  Agents agents;
  agents.resize(n);
  const FacePoint p = locate_on_flat(mesh, domain, {0.5, 0.3});
  for (int a = 0; a < n; ++a) {
    agents.face[a] = p.face;
    agents.position[a] = p.position;
    agents.heading[a] = direction_in_face(mesh, p.face, Eigen::Vector3d::UnitY());
    agents.time_since_decision[a] = 0.0;
    agents.accumulated_turn[a] = 0.0;
  }
  Agents again = agents;
  // Five steps of 0.01 s: exactly one decision at f = 20.
  for (std::uint32_t s = 0; s < 5; ++s) sense_and_steer(domain, params, u, 0.01, 4, s, agents);
  for (std::uint32_t s = 0; s < 5; ++s) sense_and_steer(domain, params, u, 0.01, 4, s, again);
  int left = 0;
  for (int a = 0; a < n; ++a) {
    const double angle = angle_on_flat(mesh, agents.face[a], agents.heading[a]);
    ASSERT_TRUE(std::abs(angle - 91.0) < 1e-6 || std::abs(angle - 89.0) < 1e-6) << angle;
    left += angle > 90.0;
    EXPECT_EQ(agents.heading[a], again.heading[a]);
  }
  EXPECT_NEAR(left, n / 2.0, 4.5 * std::sqrt(n / 4.0));
}

TEST(ReferenceAgents, SensorsStopAtBoundariesAndReadNothing) {
  const InputMesh mesh = load_mesh("shape:square");
  const SurfaceDomain domain = domain_as_is(mesh);
  const IntrinsicVertexData<double> u(static_cast<size_t>(domain.vertex_count), 1.0);
  // 0.03 from the right edge, facing it: a 0.05 sensor crosses the edge, a 0.02 one does not.
  const FacePoint p = locate_on_flat(mesh, domain, {0.97, 0.5});
  const Eigen::Vector2d east = direction_in_face(mesh, p.face, Eigen::Vector3d::UnitX());
  const Eigen::Vector2d north = direction_in_face(mesh, p.face, Eigen::Vector3d::UnitY());
  EXPECT_EQ(read_sensor(domain, u, p.face, p.position, east, 0.05), 0.0);
  EXPECT_NEAR(read_sensor(domain, u, p.face, p.position, east, 0.02), 1.0, 1e-12);
  EXPECT_NEAR(read_sensor(domain, u, p.face, p.position, north, 0.3), 1.0, 1e-12);
  // All three at once: heading east, the centre sensor is out, the side ones (at +-80 degrees, so
  // they travel only 0.05 cos 80 towards the edge) are in.
  const SensorReadings r = read_sensors(domain, u, p.face, p.position, east, 80.0 * kDegree, 0.05);
  EXPECT_EQ(r.centre, 0.0);
  EXPECT_NEAR(r.left, 1.0, 1e-12);
  EXPECT_NEAR(r.right, 1.0, 1e-12);
}

TEST(ReferenceAgents, DepositAlongThePathMatchesTheLineIntegralOfEq4) {
  // Reference: the line integral of the hat functions along the path by brute force (the amount
  // split into 4000 equal point deposits along the path), against the per-segment midpoint rule.
  const InputMesh mesh = load_mesh("shape:square");
  const SurfaceDomain domain = domain_as_is(mesh);
  const FacePoint p = locate_on_flat(mesh, domain, {0.31, 0.42});
  const Eigen::Vector2d dir = direction_in_face(mesh, p.face, Eigen::Vector3d(0.8, 0.6, 0.0));
  const double length = 0.17;  // crosses several of the square's 1/32 cells
  std::vector<TraceSegment> segments;
  const TraceResult r = trace(domain, p.face, p.position, dir, length, BoundaryRule::Reflect, &segments);
  ASSERT_GT(r.face_crossings, 5);
  IntrinsicVertexData<double> midpoint(static_cast<size_t>(domain.vertex_count), 0.0), brute(midpoint.size(), 0.0);
  const double amount = 2.5;
  deposit_along_path(domain, segments, amount, p.face, p.position, midpoint);
  const int pieces = 4000;
  for (int i = 0; i < pieces; ++i) {
    const TraceResult q = trace(domain, p.face, p.position, dir, length * (i + 0.5) / pieces, BoundaryRule::Reflect);
    const Eigen::Vector3d b = barycentric_in_face(domain, q.face, q.position);
    for (int k = 0; k < 3; ++k) brute[domain.face_vertices[q.face][k]] += amount / pieces * b[k];
  }
  double total = 0.0;
  for (int v = 0; v < domain.vertex_count; ++v) {
    total += midpoint[v];
    EXPECT_NEAR(midpoint[v], brute[v], 2e-4 * amount) << "vertex " << v;
  }
  EXPECT_NEAR(total, amount, 1e-12);
  // A path of no length is a point deposit where the agent stands.
  IntrinsicVertexData<double> still(midpoint.size(), 0.0);
  deposit_along_path(domain, {}, 1.0, p.face, p.position, still);
  const Eigen::Vector3d b = barycentric_in_face(domain, p.face, p.position);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(still[domain.face_vertices[p.face][k]], b[k], 1e-15);
}

TEST(ReferenceAgents, ActivationFraction) {
  EXPECT_EQ(active_fraction(0.0, 0.01, 0.2), 0.0);
  EXPECT_EQ(active_fraction(0.2, 0.01, 0.2), 1.0);
  EXPECT_EQ(active_fraction(0.5, 0.01, 0.2), 1.0);
  EXPECT_NEAR(active_fraction(0.195, 0.01, 0.2), 0.5, 1e-12);
  // An age summed from twenty 0.01 steps is 0.2 up to rounding: still active for the whole step.
  double age = 0.0;
  for (int i = 0; i < 20; ++i) age += 0.01;
  EXPECT_NEAR(active_fraction(age, 0.01, 0.2), 1.0, 1e-12);
  EXPECT_EQ(active_fraction(1.0, 0.01, 0.0), 1.0);
}

TEST(ReferenceAgents, ReflectionKeepsEveryAgentInsideItsFace) {
  // Fast agents on the small square hit its boundary all the time; after every step every agent
  // must sit inside its face (barycentric coordinates >= 0 up to rounding).
  const InputMesh mesh = load_mesh("shape:square");
  const SurfaceDomain domain = domain_as_is(mesh);
  Scene scene = plain_scene();
  scene.agent_model().agents = 500;
  scene.agent_model().parameters[Param::move_rate] = 2.0;  // 0.02 per step: a boundary every ~25 steps
  SimulationSettings settings{scene.agent_model().agents, scene.time_step, 2, Integrator::Forward};
  ReferenceAgentSimulation sim(domain, VertexParameters::constant(scene.agent_model().parameters, domain.vertex_count), settings);
  double worst = 0.0;
  for (int s = 0; s < 200; ++s) {
    sim.step();
    for (int a = 0; a < sim.agents().count(); ++a) {
      const int f = sim.agents().face[a];
      ASSERT_TRUE(f >= 0 && f < domain.face_count);
      worst = std::min(worst, barycentric_in_face(domain, f, sim.agents().position[a]).minCoeff());
      ASSERT_NEAR(sim.agents().heading[a].norm(), 1.0, 1e-9);
    }
  }
  EXPECT_GE(worst, -1e-9);
  // And they did meet the boundary, often.
  EXPECT_GT(sim.counters().boundary_hits, 500);
}

TEST(ReferenceAgents, ZeroTurnRateWalksGeodesics) {
  // Flat square: a straight line (reflections aside, so keep the walk short of the boundary).
  {
    const InputMesh mesh = load_mesh("shape:square");
    const SurfaceDomain domain = domain_as_is(mesh);
    Agents agents;
    agents.resize(1);
    const FacePoint p = locate_on_flat(mesh, domain, {0.1, 0.2});
    agents.face[0] = p.face;
    agents.position[0] = p.position;
    const Eigen::Vector3d dir = Eigen::Vector3d(0.6, 0.7, 0).normalized();
    agents.heading[0] = direction_in_face(mesh, p.face, dir);
    std::vector<TraceSegment> segments;
    const Eigen::Vector3d start(0.1, 0.2, 0.0);
    for (int s = 0; s < 100; ++s) {
      move_agent(domain, agents, 0, 0.009, segments);
      const Eigen::Vector3d x = point_in_3d(mesh, domain, agents.face[0], agents.position[0]);
      const Eigen::Vector3d off = (x - start) - (x - start).dot(dir) * dir;
      ASSERT_LT(off.norm(), 1e-9) << "step " << s;
      ASSERT_NEAR((x - start).dot(dir), 0.009 * (s + 1), 1e-9);
    }
  }
  // Sphere (an icosphere, whose flat faces approximate the sphere): with turn_rate 0 a simulated
  // agent, pheromone and all, stays on one great circle: in a plane through the centre.
  {
    const InputMesh mesh = load_mesh("shape:sphere");
    const SurfaceDomain domain = domain_as_is(mesh);
    Scene scene = plain_scene();
    scene.agent_model().parameters[Param::turn_rate] = 0.0;
    scene.agent_model().parameters[Param::mean_lifetime] = std::numeric_limits<double>::infinity();
    scene.agent_model().agents = 50;
    scene.agent_model().parameters[Param::move_rate] = 0.5;
    SimulationSettings settings{scene.agent_model().agents, scene.time_step, 6, Integrator::Forward};
    VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, domain.vertex_count);
    ReferenceAgentSimulation sim(domain, params, settings);
    const Eigen::Vector3d x0 = point_in_3d(mesh, domain, sim.agents().face[0], sim.agents().position[0]);
    const Eigen::Vector3d d0 = direction_in_3d(mesh, sim.agents().face[0], sim.agents().heading[0]);
    const Eigen::Vector3d normal = x0.cross(d0).normalized();
    double worst = 0.0;
    for (int s = 0; s < 600; ++s) {  // 3 m: about half a great circle of the unit sphere
      sim.step();
      const Eigen::Vector3d x = point_in_3d(mesh, domain, sim.agents().face[0], sim.agents().position[0]);
      worst = std::max(worst, std::abs(normal.dot(x)) / x.norm());
    }
    // Out-of-plane drift of a straight walk on the icosphere (level 4, edges ~0.08) is ~0.003, from
    // the polyhedral approximation; a turn of just 0.2 rad/s takes the walk 0.38 out of the plane.
    EXPECT_LT(worst, 0.01);
  }
}

}  // namespace
}  // namespace physarum
