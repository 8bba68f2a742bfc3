#include "common/vertex_parameters.hpp"

#include <algorithm>
#include <limits>

namespace physarum {

VertexParameters VertexParameters::constant(const Scene& scene, int vertex_count) {
  const size_t n = static_cast<size_t>(std::max(vertex_count, 0));
  VertexParameters p;
  p.diffuse_rate.assign(n, scene.diffuse_rate);
  p.decay_rate.assign(n, scene.decay_rate);
  p.sensor_distance.assign(n, scene.sensor_distance);
  p.sensor_angle.assign(n, scene.sensor_angle);
  p.move_rate.assign(n, scene.move_rate);
  p.turn_rate.assign(n, scene.turn_rate);
  p.turn_frequency.assign(n, scene.turn_frequency);
  p.deposit_rate.assign(n, scene.deposit_rate);
  p.mean_lifetime.assign(n, scene.mean_lifetime.value_or(std::numeric_limits<double>::infinity()));
  p.activation_time.assign(n, scene.activation_time);
  return p;
}

bool is_uniform(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
}

}  // namespace physarum
