#pragma once
// The sheet's rest state: what it would be if each piece were free. Growth is a change of this
// state, never of the positions: each face keeps its own rest metric (the 2 x 2 Gram matrix of its
// rest edge vectors e1 = x1 - x0, e2 = x2 - x0 in the face's corner order), so neighbouring faces may
// grow by different amounts and the sheet buckles to reconcile them. The rest dihedral angles are
// those of the initial sheet (0 for a flat one): growth here is in-plane, as in the paper (no
// differential growth between the sheet's two sides).
#include "common/shell/shell_topology.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace physarum {

struct ShellRestState {
  std::vector<Eigen::Matrix2d> face_metric;  // per face
  std::vector<double> hinge_angle;           // per hinge
};

// The rest state in which `positions` is unstressed.
ShellRestState rest_state_of(const ShellTopology& topology, const std::vector<Eigen::Vector3d>& positions);

// The squared rest length of the edge opposite `corner` in a face with rest metric `metric`.
double rest_edge_length_squared(const Eigen::Matrix2d& metric, int corner);
// The inverse: the rest metric of a face whose squared rest edge lengths are `opposite_squared[c]`
// for the edge opposite corner c.
Eigen::Matrix2d metric_from_edge_lengths(const std::array<double, 3>& opposite_squared);

// The bending weight |ebar|^2 / (Abar_0 + Abar_1) of a hinge (common/shell/hinge_bending.hpp): the
// edge's squared rest length is the mean of what its two faces' metrics say (they differ when the
// faces grew differently).
double hinge_weight(const ShellHinge& hinge, const ShellRestState& rest);

// The total rest area (sum of the faces' sqrt(det) / 2).
double rest_area(const ShellRestState& rest);

// A face's rest metric after growing by `along` in the direction `direction` and by `across`
// perpendicular to it (both > 0; 1 = no growth; along = across is isotropic growth, the metric scaled
// by along^2). `direction` is given by its coefficients on the face's rest edge vectors e1, e2; its
// length does not matter (zero: isotropic growth by `across`).
Eigen::Matrix2d grown_metric(const Eigen::Matrix2d& metric, double along, double across,
                             const Eigen::Vector2d& direction);

}  // namespace physarum
