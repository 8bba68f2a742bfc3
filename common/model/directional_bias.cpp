#include "common/model/directional_bias.hpp"

#include "common/model/domain_sampling.hpp"
#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace physarum {

double angle_from_closest_copy(const Eigen::Vector2d& heading, const Eigen::Vector2d& direction, int symmetry) {
  // The angle from the direction to the heading, folded onto the nearest copy: the copies are
  // period 2pi/n apart, so subtracting the nearest multiple of the period leaves the signed angle
  // to the closest one.
  const double period = 2.0 * std::numbers::pi / symmetry;
  const double angle = std::atan2(direction.x() * heading.y() - direction.y() * heading.x(), direction.dot(heading));
  return angle - period * std::round(angle / period);
}

double bias_turn(const Eigen::Vector2d& heading, const Eigen::Vector2d& direction, double strength, int symmetry,
                 double dt) {
  if (!(strength > 0.0) || direction.squaredNorm() == 0.0) return 0.0;
  return -angle_from_closest_copy(heading, direction, symmetry) * -std::expm1(-strength * dt);
}

Eigen::Vector2d heading_along_bias(const Eigen::Vector2d& direction, int symmetry, double u) {
  const double length = direction.norm();
  if (length == 0.0) return heading_from_uniform(u);
  const int copy = std::min(static_cast<int>(u * symmetry), symmetry - 1);
  const double angle = std::atan2(direction.y(), direction.x()) + 2.0 * std::numbers::pi * copy / symmetry;
  return {std::cos(angle), std::sin(angle)};
}

void check_directional_bias(const SurfaceDomain& domain, const DirectionalBias& bias) {
  if (bias.symmetry < 1 || bias.symmetry > 8)
    throw InputError("bias: symmetry " + std::to_string(bias.symmetry) + " must be 1..8");
  if (bias.direction.size() != static_cast<size_t>(domain.face_count))
    throw InputError("bias: " + std::to_string(bias.direction.size()) + " directions for " +
                     std::to_string(domain.face_count) + " faces");
  if (bias.strength.size() != static_cast<size_t>(domain.vertex_count))
    throw InputError("bias: " + std::to_string(bias.strength.size()) + " strengths for " +
                     std::to_string(domain.vertex_count) + " vertices");
  for (size_t f = 0; f < bias.direction.size(); ++f)
    if (!std::isfinite(bias.direction[f][0]) || !std::isfinite(bias.direction[f][1]))
      throw InputError("bias: the direction of face " + std::to_string(f) + " is not finite");
  for (size_t i = 0; i < bias.strength.size(); ++i)
    if (!std::isfinite(bias.strength[i]) || bias.strength[i] < 0.0)
      throw InputError("bias: the strength at vertex " + std::to_string(i) + " is " + std::to_string(bias.strength[i]) +
                       " (must be finite and >= 0)");
}

}  // namespace physarum
