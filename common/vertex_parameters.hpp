#pragma once
// Every scalar model parameter stored per intrinsic vertex (paper Sec. 3.3, "Parameter maps"), so a
// spatially varying map later changes only how these arrays are filled, not who reads them. Built
// constant from a Scene by default. Units are SI, angles in radians (as in Scene).
#include "common/scene.hpp"

#include <vector>

namespace physarum {

struct VertexParameters {
  // ---- pheromone (Eq. 6/7: the diagonals of R_dif and R_dec) ----
  std::vector<double> diffuse_rate;  // m^2/s
  std::vector<double> decay_rate;    // 1/s

  // ---- agents: interpolated at an agent's position (barycentric over its face's corners) ----
  std::vector<double> sensor_distance;  // m
  std::vector<double> sensor_angle;     // rad
  std::vector<double> move_rate;        // m/s
  std::vector<double> turn_rate;        // rad/s
  std::vector<double> turn_frequency;   // 1/s
  std::vector<double> deposit_rate;     // amount/s per agent
  // s; +infinity where there is no turnover, so the exposure increment dt / mean_lifetime is 0.
  std::vector<double> mean_lifetime;
  std::vector<double> activation_time;  // s

  int vertex_count() const { return static_cast<int>(decay_rate.size()); }

  // Every parameter constant, equal to the scene's value, on `vertex_count` vertices.
  static VertexParameters constant(const Scene& scene, int vertex_count);
};

// True when every entry of `values` equals the first (an empty array counts as uniform). Lets a
// consumer pick a cheaper or symmetric path when a map is in fact constant.
bool is_uniform(const std::vector<double>& values);

}  // namespace physarum
