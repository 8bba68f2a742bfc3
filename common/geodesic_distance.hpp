#pragma once
// Computing the geodesic distance map source (common/geodesic_distance_source.hpp) on a surface: the
// value at every intrinsic vertex is its distance along the surface to the nearest seed, in
// simulation units (after scale_to_area, like every length the simulation uses).
//   heat: common/heat_geodesic.hpp (smooth; factorizations kept per time factor for the surface)
//   fmm:  common/fast_marching.hpp (exact on flat parts; first order on curved ones)
#include "common/element_data.hpp"
#include "common/fast_marching.hpp"
#include "common/geodesic_distance_source.hpp"
#include "common/heat_geodesic.hpp"
#include "common/seed_set.hpp"

#include <map>
#include <memory>
#include <string>

namespace physarum {

// The solvers of one surface, built the first time a method (and time factor) asks for them and
// kept for every later map on the same surface: the heat method's factorizations are its cost.
class GeodesicSolvers {
 public:
  explicit GeodesicSolvers(const SurfaceDomain& domain) : domain_(domain) {}
  const HeatGeodesicSolver& heat(double time_factor);
  const FastMarchingGeodesics& fast_marching();

 private:
  const SurfaceDomain& domain_;
  std::map<double, std::unique_ptr<HeatGeodesicSolver>> heat_;
  std::unique_ptr<FastMarchingGeodesics> fast_marching_;
};

// The distance map. InputError "WHERE: ..." for an empty seed set (seed_vertices' errors) or a piece
// of the surface that no seed reaches.
IntrinsicVertexData<double> geodesic_distance(const GeodesicDistanceSource& source, const SeedSurface& surface,
                                              GeodesicSolvers& solvers, const std::string& where);

}  // namespace physarum
