#include "common/growth/face_growth.hpp"

#include "common/shell/membrane_energy.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <cmath>

namespace physarum {

namespace {

Eigen::Matrix2d grown_by_edges(const Eigen::Matrix2d& metric, const std::array<double, 3>& stretch) {
  std::array<double, 3> squared{};
  for (int c = 0; c < 3; ++c) squared[c] = rest_edge_length_squared(metric, c) * stretch[c] * stretch[c];
  const Eigen::Matrix2d grown = metric_from_edge_lengths(squared);
  if (grown.determinant() > 0.0) return grown;
  const double mean = (stretch[0] + stretch[1] + stretch[2]) / 3.0;
  return mean * mean * metric;
}

}  // namespace

void grow_faces(ShellRestState& rest, const FaceGrowth& growth) {
  if (!growth.edge.empty()) {
    for (std::size_t f = 0; f < rest.face_metric.size(); ++f) rest.face_metric[f] = grown_by_edges(rest.face_metric[f], growth.edge[f]);
    return;
  }
  for (std::size_t f = 0; f < rest.face_metric.size(); ++f) {
    const Eigen::Vector2d direction = growth.direction.empty() ? Eigen::Vector2d::Zero() : growth.direction[f];
    rest.face_metric[f] = grown_metric(rest.face_metric[f], growth.along[f], growth.across[f], direction);
  }
}

std::vector<std::array<double, 3>> edge_stretches(const ShellTopology& topology, const std::vector<double>& vertex_stretch,
                                                  double power) {
  std::vector<std::array<double, 3>> stretch(topology.faces.size());
  for (std::size_t f = 0; f < topology.faces.size(); ++f) {
    const auto& t = topology.faces[f];
    for (int c = 0; c < 3; ++c) {
      const double mean = 0.5 * (vertex_stretch[static_cast<std::size_t>(t[(c + 1) % 3])] +
                                 vertex_stretch[static_cast<std::size_t>(t[(c + 2) % 3])]);
      stretch[f][static_cast<std::size_t>(c)] = std::pow(mean, power);
    }
  }
  return stretch;
}

std::vector<Eigen::Vector2d> face_directions(const ShellTopology& topology, const std::vector<Eigen::Vector3d>& positions,
                                             const std::vector<Eigen::Vector3d>& direction) {
  std::vector<Eigen::Vector2d> coefficients(topology.faces.size(), Eigen::Vector2d::Zero());
  for (std::size_t f = 0; f < topology.faces.size(); ++f) {
    const auto& t = topology.faces[f];
    Eigen::Matrix<double, 3, 2> edges;
    edges.col(0) = positions[t[1]] - positions[t[0]];
    edges.col(1) = positions[t[2]] - positions[t[0]];
    const Eigen::Matrix2d metric = edges.transpose() * edges;
    coefficients[f] = metric.ldlt().solve(edges.transpose() * direction[f]);
  }
  return coefficients;
}

std::vector<double> rest_vertex_masses(const ShellTopology& topology, const ShellRestState& rest) {
  std::vector<double> mass(static_cast<std::size_t>(topology.vertex_count), 0.0);
  for (std::size_t f = 0; f < topology.faces.size(); ++f) {
    const double third = metric_area(rest.face_metric[f]) / 3.0;
    for (int v : topology.faces[f]) mass[static_cast<std::size_t>(v)] += third;
  }
  return mass;
}

void dilute(std::vector<double>& values, const std::vector<double>& old_mass, const std::vector<double>& new_mass) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (new_mass[i] > 0.0) values[i] *= old_mass[i] / new_mass[i];
}

}  // namespace physarum
