#pragma once
// The surface domain most tests simulate on: a mesh (file or shape:NAME) flipped to intrinsic
// Delaunay, so its cotan weights are non-negative, without scaling or refinement — through the
// loader every command uses (common/setup/scene_surface.hpp).
#include "common/setup/scene_surface.hpp"
#include "common/surface/surface_domain.hpp"

#include <string>

namespace physarum::testing {

inline SurfaceDomain delaunay_domain(const std::string& spec) {
  SurfaceSpec surface;
  surface.mesh = spec;
  return prepare_surface(surface).domain;
}

}  // namespace physarum::testing
