#pragma once
// A flat sheet compressed in its plane is in equilibrium, unstable but exact: Newton's method started
// there never leaves the plane, because no force points out of it. Real sheets are never perfectly
// flat; before each growth step the vertices are nudged along their normals by a small random amount
// (reproducible: Philox keyed by the seed and the vertex, counter = the growth step), which lets the
// solve find the buckled equilibrium where one exists and decays back where the flat one is stable.
#include "common/shell/shell_topology.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace physarum {

// Area-weighted vertex normals (unit; zero for a vertex with no area).
std::vector<Eigen::Vector3d> vertex_normals(const ShellTopology& topology, const std::vector<Eigen::Vector3d>& positions);

// Moves every vertex along its normal by a uniform amount in [-amplitude, amplitude].
void perturb_out_of_plane(const ShellTopology& topology, std::vector<Eigen::Vector3d>& positions, double amplitude,
                          std::uint32_t seed, std::uint32_t growth_step);

}  // namespace physarum
