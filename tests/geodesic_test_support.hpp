#pragma once
// Known answers for the geodesic tests: great-circle distance on the unit sphere, Euclidean distance
// on flat meshes, and the largest error of a computed distance against them.
#include "common/element_data.hpp"
#include "common/input_mesh.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace physarum::testing {

// arccos(p.q) for unit vectors: the distance along the unit sphere.
inline double great_circle(const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  return std::acos(std::clamp(p.dot(q), -1.0, 1.0));
}

// max over vertices of |computed[v] - exact(position[v])| (intrinsic vertex v sits on input vertex v:
// meshes taken as they are, without refinement).
template <class Exact>
double max_error(const InputMesh& mesh, const IntrinsicVertexData<double>& computed, Exact exact) {
  double worst = 0.0;
  for (int v = 0; v < mesh.vertex_count(); ++v)
    worst = std::max(worst, std::abs(computed[static_cast<size_t>(v)] - exact(mesh.positions[static_cast<size_t>(v)])));
  return worst;
}

}  // namespace physarum::testing
