#pragma once
// An elevation proxy from the surface's extrinsic shape (paper Sec. 3.3, Fig. 19: patterns that
// follow ridges and valleys): how far each point of the INPUT mesh stands out of a smoothed,
// volume-preserving copy of itself. The "elevation" map source of common/maps/map_definition.hpp.
//
//  1. Smooth: implicit mean-curvature flow of the input's vertex positions X for `time`, in `steps`
//     backward-Euler steps (M_k + h L) X_{k+1} = M_k X_k, h = time D^2 / steps. L is the cotan
//     Laplacian of the INPUT geometry, kept fixed, and M_k the lumped mass of the current copy
//     (Kazhdan, Solomon & Ben-Chen 2012, "Can mean-curvature flow be made non-singular?"): with L
//     fixed the flow cannot pinch or degenerate, whatever the time.
//     Units: D is the input's bounding-box diagonal, so `time` is a fraction of D^2 and the same
//     value smooths a mesh the same way whatever its units or scale_to_area. Detail of size w is
//     mostly gone once time D^2 exceeds about (w / 2 pi)^2; time ~ 1e-3 keeps the body's shape and
//     removes its small bumps, time ~ 1e-2 leaves little more than an ellipsoid.
//  2. Keep the volume: mean-curvature flow shrinks a closed surface, so each CLOSED connected
//     component of the copy is scaled about its own volume centroid until it encloses the volume
//     the original component encloses. An OPEN component (one with boundary) encloses no volume:
//     its boundary vertices are held in place during the flow instead, so the copy is the
//     membrane spanning the same boundary (a height field's base), and it is not rescaled.
//  3. Measure: the signed distance of each input vertex to its smoothed copy along the input's
//     outward vertex normal (area-weighted face normals), d = (x - x_smooth) . n: > 0 on bumps and
//     ridges, < 0 in valleys and pits.
//  4. Normalise to 0..1: value = 0.5 + (d - mid) / max(spread, floor), with mid and spread the
//     midpoint and width of d's range and floor = kElevationReliefFloor x D. Relief above the floor
//     spans exactly 0..1; relief below it (a sphere, a plane: what remains is the discretisation's
//     own noise) stays near 0.5 instead of being stretched into a false pattern.
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace physarum {

// The least relief, as a fraction of the bounding-box diagonal, that is spread over the whole 0..1
// range (step 4 above).
inline constexpr double kElevationReliefFloor = 1e-3;

struct ElevationProxy {
  std::vector<Eigen::Vector3d> smoothed;        // the volume-preserving smoothed copy, per input vertex
  InputVertexData<double> signed_distance;      // d, in input units
  InputVertexData<double> value;                // normalised, in [0, 1]
};

// Steps 1-4 on `input`. `where` starts every message. InputError when time <= 0 or is not finite,
// steps < 1, the mesh has no extent, a face is degenerate, or a closed component's copy collapses
// to no volume.
ElevationProxy elevation_proxy(const InputMesh& input, double time, int steps, const std::string& where);

// The volume enclosed by the triangles `faces` of a closed surface (divergence theorem; > 0 when
// they are counter-clockwise seen from outside).
double enclosed_volume(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<int, 3>>& faces);

}  // namespace physarum
