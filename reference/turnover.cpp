#include "reference/turnover.hpp"

#include "common/domain_sampling.hpp"
#include "common/random_streams.hpp"

#include <cmath>
#include <limits>

namespace physarum {

void respawn_agent(const SurfaceDomain& domain, std::uint32_t seed, std::uint32_t step, int a, Agents& agents) {
  const auto id = static_cast<std::uint32_t>(a);
  const FacePoint p = sample_surface_point(domain, agent_random_words(seed, id, step, RandomPurpose::RespawnPlacement, 0),
                                           agent_random_words(seed, id, step, RandomPurpose::RespawnPlacement, 1));
  const PhiloxWords state = agent_random_words(seed, id, step, RandomPurpose::RespawnState, 0);
  agents.face[a] = p.face;
  agents.position[a] = p.position;
  agents.heading[a] = heading_from_uniform(first_uniform(state));
  agents.age[a] = 0.0;
  agents.exposure[a] = 0.0;
  agents.exposure_threshold[a] = exponential_exposure(second_uniform(state));
  // A newborn starts a fresh decision period (it has no turn to carry over from its previous life).
  agents.time_since_decision[a] = 0.0;
  agents.accumulated_turn[a] = 0.0;
}

int advance_turnover(const SurfaceDomain& domain, const IntrinsicVertexData<double>& hazard_rate, double dt, std::uint32_t seed,
                     std::uint32_t step, Agents& agents, std::vector<double>* lifetimes) {
  int respawned = 0;
  for (int a = 0; a < agents.count(); ++a) {
    agents.age[a] += dt;
    const double hazard = interpolate_vertex_field(domain, hazard_rate, agents.face[a], agents.position[a]);
    if (hazard == 0.0) continue;  // no turnover here: the exposure stays put
    agents.exposure[a] += dt * hazard;
    if (agents.exposure[a] >= agents.exposure_threshold[a]) {
      if (lifetimes) lifetimes->push_back(agents.age[a]);
      respawn_agent(domain, seed, step, a, agents);
      ++respawned;
    }
  }
  return respawned;
}

}  // namespace physarum
