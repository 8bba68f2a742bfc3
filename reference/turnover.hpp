#pragma once
// Agent turnover (paper Sec. 3.2, Fig. 2d; hazard form of Sec. 3.3). Each agent carries an exposure
// lambda that grows by dt / tau(x) (the time step normalised by the local mean lifetime, i.e. the
// integrated hazard rate 1/tau), and an exposure threshold lambda_t = -ln X, X uniform in (0, 1).
// Once lambda >= lambda_t the agent decays and is reborn at a uniformly random point of the surface
// (face by the area-weighted alias table, point by the square-root trick), with a random heading,
// age 0, exposure 0 and a fresh threshold. With a constant tau, lifetimes are Exp(tau).
#include "common/surface_domain.hpp"
#include "common/agents.hpp"
#include "common/element_data.hpp"

#include <cstdint>
#include <vector>

namespace physarum {

// Rebirth of agent a in step `step` (RandomPurpose::RespawnPlacement / RespawnState).
void respawn_agent(const SurfaceDomain& domain, std::uint32_t seed, std::uint32_t step, int a, Agents& agents);

// Ages every agent by dt, grows its exposure by dt times the hazard at its position, and respawns
// those whose exposure reached the threshold. Returns how many were respawned. When `lifetimes` is
// given, the age at decay of every respawned agent is appended (for tests and statistics).
int advance_turnover(const SurfaceDomain& domain, const IntrinsicVertexData<double>& hazard_rate, double dt, std::uint32_t seed,
                     std::uint32_t step, Agents& agents, std::vector<double>* lifetimes = nullptr);

}  // namespace physarum
