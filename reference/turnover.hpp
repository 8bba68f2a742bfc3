#pragma once
// Agent turnover (paper Sec. 3.2, Fig. 2d; hazard form of Sec. 3.3). Each agent carries an exposure
// lambda that grows by dt / tau(x) (the time step normalised by the local mean lifetime, i.e. the
// integrated hazard rate 1/tau), and an exposure threshold lambda_t = -ln X, X uniform in (0, 1).
// Once lambda >= lambda_t the agent decays and is reborn at a uniformly random point of the surface
// (face by the area-weighted alias table, point by the square-root trick), with a random heading,
// age 0, exposure 0 and a fresh threshold. With a constant tau, lifetimes are Exp(tau).
//
// Controls (Sec. 3.3): with spawn weights or sinks the rebirth point follows the linear spawn
// density (common/model/spawn_distribution.hpp), and with SpawnHeading::Bias the newborn faces along the
// local bias direction (common/model/directional_bias.hpp). A sink (hazard +infinity at any corner of the
// agent's face: mean lifetime 0 there) removes an agent at once, whatever its threshold, and so does
// a boundary with BoundaryBehaviour::Terminate (the caller flags those agents): either way the agent
// is reborn in the same step, so a sink face holds no agent at the end of a step.
#include "common/model/simulation_controls.hpp"
#include "common/model/spawn_distribution.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/model/agents.hpp"
#include "common/base/element_data.hpp"

#include <cstdint>
#include <vector>

namespace physarum {

// Where and how agents are (re)born. The default is the base model: uniform by area, random heading.
struct SpawnRule {
  const SpawnDistribution* distribution = nullptr;  // null or unweighted: uniform by area
  SpawnHeading heading = SpawnHeading::Random;
  const DirectionalBias* bias = nullptr;  // read when heading is Bias
};

// The heading a newborn at `p` takes from the uniform u of its heading draw: random, or along the
// bias (SpawnHeading::Bias).
Eigen::Vector2d spawn_heading(const SpawnRule& rule, const FacePoint& p, double u);

// Rebirth of agent a in step `step` (RandomPurpose::RespawnPlacement / RespawnState, and
// RespawnCorner for a weighted spawn).
void respawn_agent(const SurfaceDomain& domain, std::uint32_t seed, std::uint32_t step, int a, Agents& agents,
                   const SpawnRule& rule = {});

// Ages every agent by dt, grows its exposure by dt times the hazard at its position, and respawns
// those whose exposure reached the threshold, that stand in a sink face, or that `removed` flags
// (non-zero entries; may be null). Returns how many were respawned. When `lifetimes` is given, the
// age at decay of every respawned agent is appended (for tests and statistics). Only the agents of
// `range` (one species, whose hazard and spawn rule these are) are advanced.
int advance_turnover(const SurfaceDomain& domain, const IntrinsicVertexData<double>& hazard_rate, double dt, std::uint32_t seed,
                     std::uint32_t step, Agents& agents, std::vector<double>* lifetimes = nullptr,
                     const SpawnRule& rule = {}, const std::vector<unsigned char>* removed = nullptr,
                     AgentRange range = {});

}  // namespace physarum
