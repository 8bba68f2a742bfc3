#pragma once
// Sampling on the surface domain, shared by both backends' model: random points and headings
// (initial placement and respawn), and reading a per-vertex field at a point of a face.
#include "common/model/agents.hpp"
#include "common/base/element_data.hpp"
#include "common/base/random_streams.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>

namespace physarum {

// A point uniformly distributed over the surface (with density proportional to the domain's face
// sampler weights): the face from the alias table (two uniforms of `face_choice`), then a uniform
// point inside it by the square-root trick (two uniforms of `in_face`): with s = sqrt(r1), the point
// (1 - s) A + s (1 - r2) B + s r2 C has constant density over triangle ABC.
FacePoint sample_surface_point(const SurfaceDomain& domain, const PhiloxWords& face_choice, const PhiloxWords& in_face);

// A uniformly distributed unit direction from one uniform u in (0, 1): angle 2 pi u.
Eigen::Vector2d heading_from_uniform(double u);

// Exponentially distributed exposure with mean 1 from one uniform u in (0, 1): -ln(u).
double exponential_exposure(double u);

// Linear (barycentric) interpolation of a per-vertex field at a point of face `face` (paper
// Sec. 3.3: scalar maps live at vertices and are interpolated across faces).
double interpolate_vertex_field(const SurfaceDomain& domain, const IntrinsicVertexData<double>& vertex_values, int face,
                                const Eigen::Vector2d& position);

}  // namespace physarum
