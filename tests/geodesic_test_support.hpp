#pragma once
// Known answers for the geodesic tests: great-circle distance on the unit sphere, Euclidean distance
// on flat meshes, and the largest error of a computed distance against them.
#include "common/base/element_data.hpp"
#include "common/surface/fe_operators.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/surface/surface_domain.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
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

// On the unit sphere `mesh` (taken as it is: intrinsic vertex v on input vertex v), distance `d`
// from input vertex 0 has a gradient of unit length (within 0.05) on every face away from the source
// (0.3 rad, ~10 edges) and from its antipode, the cut locus (0.5 rad); at least half the faces checked.
inline void expect_unit_gradient_away_from_source_and_cut_locus(const InputMesh& mesh, const SurfaceDomain& domain,
                                                                 const IntrinsicVertexData<double>& d) {
  const std::vector<Eigen::Vector2d> g = face_gradients(domain, d.values());
  int checked = 0;
  for (int f = 0; f < domain.face_count; ++f) {
    const Eigen::Vector3d centre = (mesh.positions[static_cast<size_t>(domain.face_vertices[f][0])] +
                                    mesh.positions[static_cast<size_t>(domain.face_vertices[f][1])] +
                                    mesh.positions[static_cast<size_t>(domain.face_vertices[f][2])]).normalized();
    const double r = great_circle(mesh.positions[0], centre);
    if (r < 0.3 || r > std::numbers::pi - 0.5) continue;
    EXPECT_NEAR(g[static_cast<size_t>(f)].norm(), 1.0, 0.05) << "face " << f << " at " << r << " rad";
    ++checked;
  }
  EXPECT_GT(checked, domain.face_count / 2);
}

}  // namespace physarum::testing
