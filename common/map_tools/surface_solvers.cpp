#include "common/map_tools/surface_solvers.hpp"

#include "common/numerics/shared_cholesky.hpp"

namespace physarum {

const HeatGeodesicSolver& SurfaceSolvers::heat(double time_factor) {
  auto& solver = heat_[time_factor];
  if (!solver) solver = std::make_unique<HeatGeodesicSolver>(domain_, time_factor, &laplacian_ordering());
  return *solver;
}

const FastMarchingGeodesics& SurfaceSolvers::fast_marching() {
  if (!fast_marching_) fast_marching_ = std::make_unique<FastMarchingGeodesics>(domain_);
  return *fast_marching_;
}

const std::vector<int>& SurfaceSolvers::laplacian_ordering() {
  if (!laplacian_ordering_) laplacian_ordering_ = laplacian_fill_reducing_ordering(domain_);
  return *laplacian_ordering_;
}

std::vector<int> laplacian_fill_reducing_ordering(const SurfaceDomain& domain) {
  // Only the pattern is analysed; the identity keeps the diagonal in it whatever L stores there.
  Eigen::SparseMatrix<double> pattern(domain.laplacian.to_eigen());
  for (int v = 0; v < domain.vertex_count; ++v) pattern.coeffRef(v, v) += 1.0;
  pattern.makeCompressed();
  return SharedCholesky(pattern).ordering();
}

}  // namespace physarum
