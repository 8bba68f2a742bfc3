#pragma once
// The reaction-diffusion workload that the benchmarks (bench/bench_reaction_diffusion.cpp) and the
// device check (tests/device_check) time: Pearson's Gray-Scott (D_u = 2e-5, D_v = 1e-5 on the unit
// square, F = 0.04, k = 0.06) from a rough state (u in [0.3, 1], v in [0, 0.5] at random), far
// from any steady state, so an implicit solve has real work to do in every timed step (near (1, 0)
// the warm start alone converges); on flat square grids whose interior vertices have six
// neighbours, as on a regular triangle mesh.
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "common/surface/surface_domain.hpp"
#include "pheromone_test_meshes.hpp"

#include <algorithm>
#include <map>
#include <random>

namespace physarum::testing {

// The square grid of cells x cells cells ((cells + 1)^2 vertices), built once per size.
inline const SurfaceDomain& grid_domain(int cells) {
  static std::map<int, SurfaceDomain> domains;
  auto found = domains.find(cells);
  if (found == domains.end()) found = domains.emplace(cells, make_domain(make_square_grid(cells))).first;
  return found->second;
}

// The explicit forward-Euler stability bound of diffusion rate D (Gershgorin on M^-1 L).
inline double stable_step(const SurfaceDomain& domain, double D) {
  double worst = 0.0;
  const CsrMatrix& L = domain.laplacian;
  for (int i = 0; i < domain.vertex_count; ++i)
    for (int e = L.row_start[i]; e < L.row_start[i + 1]; ++e)
      if (L.column[e] == i) worst = std::max(worst, 2.0 * L.value[e] / domain.vertex_mass[i]);
  return 2.0 / (D * worst);
}

inline ReactionDiffusionSystem rough_gray_scott(const SurfaceDomain& domain, Integrator integrator, double dt) {
  const size_t n = static_cast<size_t>(domain.vertex_count);
  ReactionDiffusionSystem s;
  s.morphogens = {"u", "v"};
  s.reaction = {"-u*v^2 + F*(1-u)", "u*v^2 - (F+k)*v"};
  s.coefficient_names = {"F", "k"};
  s.coefficients = {IntrinsicVertexData<double>(n, 0.04), IntrinsicVertexData<double>(n, 0.06)};
  for (double D : {2e-5, 1e-5}) {
    CsrMatrix K = domain.laplacian;
    for (double& v : K.value) v *= D;
    s.stiffness.push_back(K);
  }
  s.mass = domain.vertex_mass;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.3, 1.0), v(0.0, 0.5);
  s.initial = {IntrinsicVertexData<double>(n), IntrinsicVertexData<double>(n)};
  for (size_t i = 0; i < n; ++i) {
    s.initial[0][i] = u(rng);
    s.initial[1][i] = v(rng);
  }
  s.integrator = integrator;
  s.time_step = dt;
  s.substeps = 1;
  return s;
}

}  // namespace physarum::testing
