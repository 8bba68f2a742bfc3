#pragma once
// The costly, reusable pieces of the map tools on one surface (common/maps/map_evaluation.cpp keeps one
// per surface while it evaluates a scene's maps), each built the first time a map asks for it:
//   * the heat method's factorizations, per time factor (common/map_tools/heat_geodesic.hpp),
//   * fast marching's split obtuse corners (common/map_tools/fast_marching.hpp),
//   * the fill-reducing ordering of the cotan Laplacian's pattern. Every Cholesky factorization of
//     the map tools (the heat method's systems, backward-Euler diffusion, a Laplace solve on the free
//     vertices) has that pattern or a principal submatrix of it, and METIS costs about twice a
//     numeric factorization at a million faces: computed once here, each later factorization only
//     pays its own numbers (common/numerics/shared_cholesky.hpp).
#include "common/map_tools/fast_marching.hpp"
#include "common/map_tools/heat_geodesic.hpp"
#include "common/surface/surface_domain.hpp"

#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace physarum {

class SurfaceSolvers {
 public:
  explicit SurfaceSolvers(const SurfaceDomain& domain) : domain_(domain) {}
  const HeatGeodesicSolver& heat(double time_factor);
  const FastMarchingGeodesics& fast_marching();
  const std::vector<int>& laplacian_ordering();

 private:
  const SurfaceDomain& domain_;
  std::map<double, std::unique_ptr<HeatGeodesicSolver>> heat_;
  std::unique_ptr<FastMarchingGeodesics> fast_marching_;
  std::optional<std::vector<int>> laplacian_ordering_;
};

// METIS's elimination order for the pattern of the domain's Laplacian (diagonal included).
std::vector<int> laplacian_fill_reducing_ordering(const SurfaceDomain& domain);

}  // namespace physarum
