#pragma once
// The known answer of Eq. 5 per species, checked on both backends (tests/test_species_reference.cpp,
// tests/test_species_opencl.cpp): two species of different counts, deposit and decay rates, and a
// species deposits only into its own layer, so each layer's steady mean is its own species'
// U_i = N_i r_dep,i / (r_dec,i A) (no activation time).
#include "common/simulation/field_statistics.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/surface_domain.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <numeric>

namespace physarum::testing {

// Adds the two species and a sensing matrix to `scene` (one that gives no "agents" of its own).
inline void add_two_unequal_species(nlohmann::json& scene) {
  scene["species"] = {{{"agents", 400}, {"deposit_rate", 1.0}, {"decay_rate", 2.0}},
                      {{"agents", 150}, {"deposit_rate", 3.0}, {"decay_rate", 1.0}, {"diffuse_rate", 0.0005}}};
  scene["sensing"] = {{1.0, -0.5}, {-0.5, 1.0}};  // any matrix: sensing steers, it does not change the amounts
}

// Steps `sim`, built on `domain` from a scene with those species and a time step of 0.02 s, 500
// times and expects each layer's mean over the last 200 steps within 1 % of its species' U.
// `layer_mean(layer, U)` reads a layer's current mean the way the backend's own test reads it.
template <class LayerMean>
void expect_each_layer_at_its_species_u(SimulationBackend& sim, const SurfaceDomain& domain, LayerMean layer_mean) {
  const double area = std::accumulate(domain.vertex_mass.begin(), domain.vertex_mass.end(), 0.0);
  ASSERT_EQ(sim.dynamic_layer_count(), 2);
  const double U0 = uniform_steady_state(400, 1.0, 2.0, area, 0.0, 1.0);
  const double U1 = uniform_steady_state(150, 3.0, 1.0, area, 0.0, 1.0);
  double sum0 = 0.0, sum1 = 0.0;
  int samples = 0;
  for (int s = 0; s < 500; ++s) {  // 10 s: 10 decay times of the slower layer
    sim.step();
    if (s < 300) continue;
    sum0 += layer_mean(0, U0);
    sum1 += layer_mean(1, U1);
    ++samples;
  }
  EXPECT_NEAR(sum0 / samples / U0, 1.0, 0.01);
  EXPECT_NEAR(sum1 / samples / U1, 1.0, 0.01);
}

}  // namespace physarum::testing
