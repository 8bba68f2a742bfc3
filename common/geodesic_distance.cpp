#include "common/geodesic_distance.hpp"

#include "common/errors.hpp"

namespace physarum {

const HeatGeodesicSolver& GeodesicSolvers::heat(double time_factor) {
  auto& solver = heat_[time_factor];
  if (!solver) solver = std::make_unique<HeatGeodesicSolver>(domain_, time_factor);
  return *solver;
}

const FastMarchingGeodesics& GeodesicSolvers::fast_marching() {
  if (!fast_marching_) fast_marching_ = std::make_unique<FastMarchingGeodesics>(domain_);
  return *fast_marching_;
}

IntrinsicVertexData<double> geodesic_distance(const GeodesicDistanceSource& source, const SeedSurface& surface,
                                              GeodesicSolvers& solvers, const std::string& where) {
  const std::vector<int> seeds = seed_vertices(source.from, surface, where + ": \"from\"");
  try {
    if (source.method == GeodesicMethod::Heat) return solvers.heat(source.time_factor).distance(seeds);
    return solvers.fast_marching().distance(seeds);
  } catch (const InputError& error) {
    throw InputError(where + ": " + error.what());
  }
}

}  // namespace physarum
