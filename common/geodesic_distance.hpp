#pragma once
// Computing the geodesic distance map source (common/geodesic_distance_source.hpp) on a surface: the
// value at every intrinsic vertex is its distance along the surface to the nearest seed, in
// simulation units (after scale_to_area, like every length the simulation uses).
//   heat: common/heat_geodesic.hpp (smooth; factorizations kept per time factor for the surface)
//   fmm:  common/fast_marching.hpp (exact on flat parts; first order on curved ones)
#include "common/element_data.hpp"
#include "common/geodesic_distance_source.hpp"
#include "common/seed_set.hpp"
#include "common/surface_solvers.hpp"

#include <string>

namespace physarum {

// The distance map. InputError "WHERE: ..." for an empty seed set (seed_vertices' errors) or a piece
// of the surface that no seed reaches.
IntrinsicVertexData<double> geodesic_distance(const GeodesicDistanceSource& source, const SeedSurface& surface,
                                              SurfaceSolvers& solvers, const std::string& where);

}  // namespace physarum
