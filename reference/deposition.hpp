#pragma once
// Deposition along the path (paper Eq. 4, Fig. 2c): the amount an agent deposits during a step,
// r_dep * dt, is spread uniformly along the path it walked. For piecewise-linear vertex basis
// functions the line integral over each per-face segment equals a point deposit at the segment's
// midpoint, so each segment deposits (its length / the step length) of the amount at its midpoint,
// split over the face's three vertices by the midpoint's barycentric weights.
#include "common/surface/surface_domain.hpp"
#include "common/base/element_data.hpp"
#include "common/surface/trace.hpp"

#include <Eigen/Core>
#include <vector>

namespace physarum {

// Adds `amount` spread along `segments` (their lengths summing to the step length) into
// amount_per_vertex (an AMOUNT; the pheromone field divides by the vertex mass to get a
// concentration). When the path has no length (move_rate 0) the whole amount is a point deposit at
// (face, position).
void deposit_along_path(const SurfaceDomain& domain, const std::vector<TraceSegment>& segments, double amount,
                        int face, const Eigen::Vector2d& position, IntrinsicVertexData<double>& amount_per_vertex);

// The fraction of a step [age, age + dt] during which an agent of this age is active (age >= t_a,
// Sec. 3.2 "deposit activation"): 0 before, 1 after, the overlapping part in between. For t_a a
// multiple of dt this is exactly the rule "deposit when age >= t_a" at the step start, but it is
// immune to the rounding of an age summed from many dt (0.2 summed from 0.01 twenty times is not
// exactly 0.2), which would otherwise delay activation by a whole step.
double active_fraction(double age, double dt, double activation_time);

}  // namespace physarum
