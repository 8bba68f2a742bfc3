#pragma once
// Reproducible random per-vertex values for tests: a fixed seed gives the same field on every
// machine and every run.
#include "common/base/element_data.hpp"

#include <cstddef>
#include <random>

namespace physarum::testing {

// n values drawn uniformly from [lo, hi) by a Mersenne Twister seeded with `seed`.
inline IntrinsicVertexData<double> random_values(int n, unsigned seed, double lo, double hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(lo, hi);
  IntrinsicVertexData<double> v(static_cast<std::size_t>(n));
  for (double& x : v) x = uniform(rng);
  return v;
}

}  // namespace physarum::testing
