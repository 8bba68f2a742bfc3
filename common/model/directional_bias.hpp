#pragma once
// The rule of the directional bias (paper Sec. 3.3, Fig. 6; the controls themselves are
// common/model/simulation_controls.hpp), shared by both backends' model so they turn alike: each step an
// agent's heading relaxes toward the CLOSEST of the n copies of the local direction (rotated by
// k 2pi/n), d(delta)/dt = -strength delta, integrated exactly over the step. Exact, so a strong bias
// or a long step never overshoots the copy (an Euler step would for strength dt > 1, and oscillate
// for > 2). Zero-length directions and zero strength give no bias. kernels/bias.cl is the device
// copy of these functions.
#include "common/model/simulation_controls.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>

namespace physarum {

// The signed angle (radians) from the closest of the `symmetry` copies of `direction` to `heading`,
// in [-pi/n, pi/n]. Both vectors non-zero (any length).
double angle_from_closest_copy(const Eigen::Vector2d& heading, const Eigen::Vector2d& direction, int symmetry);

// How far (radians, counter-clockwise positive) one step of length dt turns the heading: -delta (1 -
// exp(-strength dt)) with delta the angle above; 0 for a zero direction or strength <= 0.
double bias_turn(const Eigen::Vector2d& heading, const Eigen::Vector2d& direction, double strength, int symmetry,
                 double dt);

// A spawn heading along the bias (SpawnHeading::Bias): copy k = floor(u n) of the normalised
// direction, u uniform in (0, 1) (the draw a random heading would use). Zero direction: the random
// heading of u, as in the base model.
Eigen::Vector2d heading_along_bias(const Eigen::Vector2d& direction, int symmetry, double u);

// InputError (naming the face or vertex) unless the bias matches the domain: one finite direction per
// face, one finite strength >= 0 per vertex, symmetry 1..8.
void check_directional_bias(const SurfaceDomain& domain, const DirectionalBias& bias);

}  // namespace physarum
