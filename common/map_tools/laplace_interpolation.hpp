#pragma once
// Laplace interpolation on the intrinsic triangulation (paper Sec. 3.3, Fig. 17: a harmonic map
// between regions held at fixed values; the "laplace" map source of common/maps/map_definition.hpp).
//
// The result u is discrete harmonic, (L u)_i = 0, at every FREE vertex and takes the given value on
// every vertex of a region (Dirichlet). Free vertices on the surface's boundary get the natural
// condition (zero normal derivative), which is what the cotan Laplacian's boundary rows say. Any
// number of regions and values is allowed. Solved on the free vertices alone,
//   L_ff u_f = -L_fb u_b,
// with a sparse Cholesky factorization (L_ff is symmetric positive definite once every connected
// component holds a fixed vertex; on the intrinsic Delaunay triangulation its off-diagonals are
// <= 0, so u stays within the regions' values: the discrete maximum principle).
#include "common/base/element_data.hpp"
#include "common/surface/surface_domain.hpp"

#include <string>
#include <vector>

namespace physarum {

// Vertices held at one value. `name` is only for messages (the region's map name).
struct DirichletRegion {
  std::string name;
  std::vector<int> vertices;  // intrinsic vertex ids
  double value = 0.0;
};

// The harmonic interpolant of the regions' values. `where` starts every message. InputError when:
// there is no region; a region holds no vertex; a vertex lies in two regions with different values
// (both named, with the vertex); a value is not finite; a connected component of the surface holds
// no fixed vertex (its values would be undetermined: the message gives the component's size and one
// of its vertices). `ordering`, when given, is the Laplacian's fill-reducing order
// (common/map_tools/surface_solvers.hpp), restricted here to the free vertices instead of running METIS.
IntrinsicVertexData<double> laplace_interpolation(const SurfaceDomain& domain, const std::vector<DirichletRegion>& regions,
                                                  const std::string& where, const std::vector<int>* ordering = nullptr);

// The connected components of the intrinsic triangulation: one label 0..count-1 per vertex, numbered
// in order of each component's lowest vertex.
struct SurfaceComponents {
  IntrinsicVertexData<int> label;
  int count = 0;
};
SurfaceComponents surface_components(const SurfaceDomain& domain);

}  // namespace physarum
