#pragma once
// Pheromone rates for the tests of the diffusion-decay PDE: the same diffusion and decay rate at
// every vertex (the other parameters stay empty; the pheromone model reads only these two).
#include "common/model/vertex_parameters.hpp"

#include <cstddef>

namespace physarum::testing {

inline VertexParameters uniform_rates(int n, double diffuse, double decay) {
  VertexParameters p;
  p[Param::diffuse_rate].assign(static_cast<std::size_t>(n), diffuse);
  p[Param::decay_rate].assign(static_cast<std::size_t>(n), decay);
  return p;
}

}  // namespace physarum::testing
