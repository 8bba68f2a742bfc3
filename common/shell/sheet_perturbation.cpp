#include "common/shell/sheet_perturbation.hpp"

#include "common/base/random_streams.hpp"

#include <Eigen/Geometry>

namespace physarum {

std::vector<Eigen::Vector3d> vertex_normals(const ShellTopology& topology, const std::vector<Eigen::Vector3d>& positions) {
  std::vector<Eigen::Vector3d> normals(positions.size(), Eigen::Vector3d::Zero());
  for (const auto& f : topology.faces) {
    const Eigen::Vector3d n = (positions[f[1]] - positions[f[0]]).cross(positions[f[2]] - positions[f[0]]);
    for (int v : f) normals[static_cast<std::size_t>(v)] += n;
  }
  for (Eigen::Vector3d& n : normals)
    if (n.squaredNorm() > 0.0) n.normalize();
  return normals;
}

void perturb_out_of_plane(const ShellTopology& topology, std::vector<Eigen::Vector3d>& positions, double amplitude,
                          std::uint32_t seed, std::uint32_t growth_step) {
  const std::vector<Eigen::Vector3d> normals = vertex_normals(topology, positions);
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const double u = first_uniform(random_words(seed, static_cast<std::uint32_t>(v), growth_step,
                                                static_cast<std::uint32_t>(RandomPurpose::ShellPerturbation)));
    positions[v] += amplitude * (2.0 * u - 1.0) * normals[v];
  }
}

}  // namespace physarum
