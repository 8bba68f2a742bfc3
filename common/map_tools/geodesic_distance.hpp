#pragma once
// Computing the geodesic distance map source (common/map_tools/geodesic_distance_source.hpp) on a surface: the
// value at every intrinsic vertex is its distance along the surface to the nearest seed, in
// simulation units (after scale_to_area, like every length the simulation uses).
//   heat: common/map_tools/heat_geodesic.hpp (smooth; factorizations kept per time factor for the surface)
//   fmm:  common/map_tools/fast_marching.hpp (exact on flat parts; first order on curved ones)
#include "common/base/element_data.hpp"
#include "common/map_tools/geodesic_distance_source.hpp"
#include "common/map_tools/seed_set.hpp"
#include "common/map_tools/surface_solvers.hpp"

#include <string>

namespace physarum {

// The distance map. InputError "WHERE: ..." for an empty seed set (seed_vertices' errors) or a piece
// of the surface that no seed reaches.
IntrinsicVertexData<double> geodesic_distance(const GeodesicDistanceSource& source, const SeedSurface& surface,
                                              SurfaceSolvers& solvers, const std::string& where);

}  // namespace physarum
