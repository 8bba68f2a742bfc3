#pragma once
// The surface domain most tests simulate on: a mesh (file or shape:NAME) flipped to intrinsic
// Delaunay, so its cotan weights are non-negative, without refinement.
#include "common/intrinsic_triangulation.hpp"
#include "common/mesh_loading.hpp"
#include "common/surface_domain.hpp"

#include <string>

namespace physarum::testing {

inline SurfaceDomain delaunay_domain(const std::string& spec) {
  IntrinsicTriangulation triangulation(load_mesh(spec));
  triangulation.flip_to_delaunay();
  return build_surface_domain(triangulation.snapshot());
}

}  // namespace physarum::testing
