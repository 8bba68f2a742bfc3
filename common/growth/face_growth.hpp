#pragma once
// Applying one growth step to the sheet's rest state: each face's rest metric grows by a stretch
// `along` a direction and `across` it (isotropic when they are equal), and the morphogens can be
// diluted so that each one's amount (concentration times the tissue's area) is conserved as the
// tissue grows (the paper's suggested future work).
#include "common/shell/rest_metric.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace physarum {

struct FaceGrowth {
  std::vector<double> along;   // per face, > 0
  std::vector<double> across;  // per face, > 0
  // Per face, the direction of `along` as coefficients on the face's rest edge vectors
  // (face_directions gives them); empty: isotropic growth by `across`.
  std::vector<Eigen::Vector2d> direction;
  // Isotropic growth given per edge instead: per face, the stretch of the edge opposite each corner
  // (the same number in both faces of an edge, so they keep agreeing on its rest length). When not
  // empty it replaces along, across and direction.
  std::vector<std::array<double, 3>> edge;
};

// Each face's rest metric grown as `growth` says (common/shell/rest_metric.hpp: grown_metric), or,
// given per edge, rebuilt from its grown rest edge lengths (a face whose grown lengths would break
// the triangle inequality, possible only where the stretch jumps across a sliver, grows by their
// mean instead).
void grow_faces(ShellRestState& rest, const FaceGrowth& growth);

// Per-edge stretches from per-vertex ones: each edge's is the mean of its ends' (the trapezoid rule
// for the edge's length in the metric stretch^2 |dx|^2), raised to `power`.
std::vector<std::array<double, 3>> edge_stretches(const ShellTopology& topology, const std::vector<double>& vertex_stretch,
                                                  double power);

// Directions given as 3D vectors on the sheet's faces (e.g. a direction map on the initial sheet)
// as coefficients on each face's edge vectors at `positions`: the least-squares solution of
// [e1 e2] c = d, i.e. d projected into the face's plane. Zero vectors stay zero.
std::vector<Eigen::Vector2d> face_directions(const ShellTopology& topology, const std::vector<Eigen::Vector3d>& positions,
                                             const std::vector<Eigen::Vector3d>& direction);

// The lumped mass of each vertex on the rest metric: a third of its faces' rest areas.
std::vector<double> rest_vertex_masses(const ShellTopology& topology, const ShellRestState& rest);

// Dilution: each concentration scaled by old mass / new mass at its vertex, so that
// sum_i mass_i u_i is unchanged for every morphogen.
void dilute(std::vector<double>& values, const std::vector<double>& old_mass, const std::vector<double>& new_mass);

}  // namespace physarum
