#include "common/map_tools/geodesic_distance.hpp"

#include "common/base/errors.hpp"

namespace physarum {

IntrinsicVertexData<double> geodesic_distance(const GeodesicDistanceSource& source, const SeedSurface& surface,
                                              SurfaceSolvers& solvers, const std::string& where) {
  const std::vector<int> seeds = seed_vertices(source.from, surface, where + ": \"from\"");
  try {
    if (source.method == GeodesicMethod::Heat) return solvers.heat(source.time_factor).distance(seeds);
    return solvers.fast_marching().distance(seeds);
  } catch (const InputError& error) {
    throw InputError(where + ": " + error.what());
  }
}

}  // namespace physarum
