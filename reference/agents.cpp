#include "reference/agents.hpp"

#include "common/random_streams.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace physarum {

void Agents::resize(int n) {
  const auto size = static_cast<size_t>(n);
  face.resize(size);
  position.resize(size);
  heading.resize(size);
  age.resize(size);
  exposure.resize(size);
  exposure_threshold.resize(size);
  time_since_decision.resize(size);
  accumulated_turn.resize(size);
}

FacePoint sample_surface_point(const SurfaceDomain& domain, const PhiloxWords& face_choice, const PhiloxWords& in_face) {
  FacePoint p;
  p.face = domain.face_sampler.sample(first_uniform(face_choice), second_uniform(face_choice));
  const std::array<Eigen::Vector2d, 3>& c = domain.face_corners[p.face];
  const double s = std::sqrt(first_uniform(in_face));
  const double r2 = second_uniform(in_face);
  p.position = (1.0 - s) * c[0] + s * (1.0 - r2) * c[1] + s * r2 * c[2];
  return p;
}

Eigen::Vector2d heading_from_uniform(double u) {
  const double angle = 2.0 * std::numbers::pi * u;
  return {std::cos(angle), std::sin(angle)};
}

double exponential_exposure(double u) { return -std::log(u); }

double interpolate_vertex_field(const SurfaceDomain& domain, const std::vector<double>& vertex_values, int face,
                                const Eigen::Vector2d& position) {
  const Eigen::Vector3d b = barycentric_in_face(domain, face, position);
  const std::array<int, 3>& v = domain.face_vertices[face];
  return b[0] * vertex_values[v[0]] + b[1] * vertex_values[v[1]] + b[2] * vertex_values[v[2]];
}

Agents initialise_agents(const SurfaceDomain& domain, const std::vector<double>& hazard_rate,
                         const std::vector<double>& turn_frequency, const std::vector<double>& turn_rate, int count,
                         std::uint32_t seed) {
  Agents agents;
  agents.resize(count);
  for (int a = 0; a < count; ++a) {
    const auto id = static_cast<std::uint32_t>(a);
    const FacePoint p = sample_surface_point(
        domain, agent_random_words(seed, id, 0, RandomPurpose::InitialPlacement, 0),
        agent_random_words(seed, id, 0, RandomPurpose::InitialPlacement, 1));
    const PhiloxWords state = agent_random_words(seed, id, 0, RandomPurpose::InitialState, 0);
    agents.face[a] = p.face;
    agents.position[a] = p.position;
    agents.heading[a] = heading_from_uniform(first_uniform(state));
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
