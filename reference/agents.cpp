#include "reference/agents.hpp"

#include "common/model/domain_sampling.hpp"
#include "common/base/random_streams.hpp"

#include <cmath>
#include <limits>

namespace physarum {

Agents initialise_agents(const SurfaceDomain& domain, const IntrinsicVertexData<double>& hazard_rate,
                         const IntrinsicVertexData<double>& turn_frequency, const IntrinsicVertexData<double>& turn_rate,
                         int count, std::uint32_t seed, const SpawnRule& rule, int first_id) {
  Agents agents;
  agents.resize(count);
  for (int a = 0; a < count; ++a) {
    const auto id = static_cast<std::uint32_t>(first_id + a);
    const PhiloxWords face_choice = agent_random_words(seed, id, 0, RandomPurpose::InitialPlacement, 0);
    const PhiloxWords in_face = agent_random_words(seed, id, 0, RandomPurpose::InitialPlacement, 1);
    const FacePoint p = rule.distribution && rule.distribution->weighted
                            ? sample_spawn_point(domain, *rule.distribution, face_choice, in_face,
                                                 agent_random_words(seed, id, 0, RandomPurpose::InitialSpawnCorner, 0))
                            : sample_surface_point(domain, face_choice, in_face);
    const PhiloxWords state = agent_random_words(seed, id, 0, RandomPurpose::InitialState, 0);
    agents.face[a] = p.face;
    agents.position[a] = p.position;
    agents.heading[a] = spawn_heading(rule, p, first_uniform(state));
    // A running population's decision clocks are out of phase: start each at a uniform point of its
    // period (with the turn accumulated so far), or every agent would decide in the same steps
    // forever when there is no turnover to scatter them.
    const PhiloxWords remaining = agent_random_words(seed, id, 0, RandomPurpose::InitialState, 1);
    const double period = 1.0 / interpolate_vertex_field(domain, turn_frequency, p.face, p.position);
    agents.time_since_decision[a] = second_uniform(remaining) * period;
    agents.accumulated_turn[a] =
        interpolate_vertex_field(domain, turn_rate, p.face, p.position) * agents.time_since_decision[a];
    const double hazard = interpolate_vertex_field(domain, hazard_rate, p.face, p.position);
    if (hazard > 0.0) {
      // Steady state without the inspection-paradox bias (see the header): elapsed and remaining
      // exposure are independent Exp(1); the threshold is their sum.
      const double elapsed = exponential_exposure(second_uniform(state));
      agents.exposure[a] = elapsed;
      agents.exposure_threshold[a] = elapsed + exponential_exposure(first_uniform(remaining));
      agents.age[a] = elapsed / hazard;  // exposure = age / tau at a constant tau
    } else {
      agents.exposure[a] = 0.0;
      agents.exposure_threshold[a] = std::numeric_limits<double>::infinity();
      agents.age[a] = 0.0;
    }
  }
  return agents;
}

}  // namespace physarum
