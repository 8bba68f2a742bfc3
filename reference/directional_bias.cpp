#include "reference/directional_bias.hpp"

#include "common/model/directional_bias.hpp"
#include "common/model/domain_sampling.hpp"
#include "reference/sensing_steering.hpp"

namespace physarum {

void apply_directional_bias(const SurfaceDomain& domain, const DirectionalBias& bias, double dt, Agents& agents) {
  for (int a = 0; a < agents.count(); ++a) {
    const int face = agents.face[a];
    const std::array<double, 2>& d = bias.direction[face];
    const double strength = interpolate_vertex_field(domain, bias.strength, face, agents.position[a]);
    const double turn = bias_turn(agents.heading[a], Eigen::Vector2d(d[0], d[1]), strength, bias.symmetry, dt);
    if (turn != 0.0) agents.heading[a] = rotate(agents.heading[a], turn).normalized();
  }
}

}  // namespace physarum
