#include "reference/turnover.hpp"

#include "common/model/directional_bias.hpp"
#include "common/model/domain_sampling.hpp"
#include "common/base/random_streams.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {

Eigen::Vector2d spawn_heading(const SpawnRule& rule, const FacePoint& p, double u) {
  if (rule.heading == SpawnHeading::Bias && rule.bias) {
    const std::array<double, 2>& d = rule.bias->direction[p.face];
    return heading_along_bias(Eigen::Vector2d(d[0], d[1]), rule.bias->symmetry, u);
  }
  return heading_from_uniform(u);
}

void respawn_agent(const SurfaceDomain& domain, std::uint32_t seed, std::uint32_t step, int a, Agents& agents,
                   const SpawnRule& rule) {
  const auto id = static_cast<std::uint32_t>(a);
  const PhiloxWords face_choice = agent_random_words(seed, id, step, RandomPurpose::RespawnPlacement, 0);
  const PhiloxWords in_face = agent_random_words(seed, id, step, RandomPurpose::RespawnPlacement, 1);
  const FacePoint p =
      rule.distribution && rule.distribution->weighted
          ? sample_spawn_point(domain, *rule.distribution, face_choice, in_face,
                               agent_random_words(seed, id, step, RandomPurpose::RespawnCorner, 0))
          : sample_surface_point(domain, face_choice, in_face);
  const PhiloxWords state = agent_random_words(seed, id, step, RandomPurpose::RespawnState, 0);
  agents.face[a] = p.face;
  agents.position[a] = p.position;
  agents.heading[a] = spawn_heading(rule, p, first_uniform(state));
  agents.age[a] = 0.0;
  agents.exposure[a] = 0.0;
  agents.exposure_threshold[a] = exponential_exposure(second_uniform(state));
  // A newborn starts a fresh decision period (it has no turn to carry over from its previous life).
  agents.time_since_decision[a] = 0.0;
  agents.accumulated_turn[a] = 0.0;
}

int advance_turnover(const SurfaceDomain& domain, const IntrinsicVertexData<double>& hazard_rate, double dt, std::uint32_t seed,
                     std::uint32_t step, Agents& agents, std::vector<double>* lifetimes, const SpawnRule& rule,
                     const std::vector<unsigned char>* removed, AgentRange range) {
  int respawned = 0;
  const int end = std::min(range.end, agents.count());
  for (int a = range.begin; a < end; ++a) {
    agents.age[a] += dt;
    const double hazard = interpolate_vertex_field(domain, hazard_rate, agents.face[a], agents.position[a]);
    // A sink corner makes the interpolated hazard +infinity, or NaN where the agent's barycentric
    // weight of that corner is exactly 0 (0 x infinity): either way not finite, and the agent goes.
    const bool forced = !std::isfinite(hazard) || (removed && (*removed)[static_cast<size_t>(a)] != 0);
    if (!forced) {
      if (hazard == 0.0) continue;  // no turnover here: the exposure stays put
      agents.exposure[a] += dt * hazard;
      if (agents.exposure[a] < agents.exposure_threshold[a]) continue;
    }
    if (lifetimes) lifetimes->push_back(agents.age[a]);
    respawn_agent(domain, seed, step, a, agents, rule);
    ++respawned;
  }
  return respawned;
}

}  // namespace physarum
