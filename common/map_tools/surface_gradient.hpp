#pragma once
// Finite-element gradients of scalar maps as maps of their own (paper Sec. 3.3, Figs. 15-18: the
// bias direction is the gradient of a distance or Laplace map; the elevation's slope is the length
// of its gradient). The "gradient" and "slope" map sources of common/maps/map_definition.hpp.
//
// A scalar map is piecewise linear over the intrinsic faces, so its gradient is one constant
// tangent vector per face (fe_operators.hpp's face_gradient), exact for a linear function. It is
// given in the face's own 2D frame (surface_domain.hpp), which is how vector maps are stored
// (map_evaluation.hpp), in map units per metre of the domain (the scene's metres after
// scale_to_area).
//
// Normalised gradients have unit length; where the gradient is zero (a flat plateau of the map,
// e.g. inside a region held at one value) there is no direction to give, so the vector stays zero,
// which the directional bias reads as "no bias here" (directional_bias.hpp).
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace physarum {

// The gradient of `values` (one per intrinsic vertex) on every intrinsic face, in its frame;
// unit length (or zero) when `normalize`.
IntrinsicFaceData<std::array<double, 2>> gradient_vector_map(const SurfaceDomain& domain,
                                                             const IntrinsicVertexData<double>& values, bool normalize);

// The same on the INPUT mesh, for writing maps back onto it: the gradient of `values` (one per input
// vertex) on every input triangle, as a 3D vector in input coordinates (map units per input unit);
// zero on a degenerate triangle.
std::vector<Eigen::Vector3d> input_face_gradients(const InputMesh& input, const InputVertexData<double>& values,
                                                  bool normalize);

// The slope: per intrinsic vertex, the area-weighted mean of |gradient| over its incident faces.
IntrinsicVertexData<double> gradient_magnitude_per_vertex(const SurfaceDomain& domain,
                                                          const IntrinsicVertexData<double>& values);

}  // namespace physarum
