#pragma once
// Points near a triangle mesh brought onto it: the closest point of one triangle, and the face of a
// whole mesh that a point on (or very near) the surface lies in.
#include "common/mesh/input_mesh.hpp"
#include "common/mesh/surface_point.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace physarum {

// The point of triangle (a, b, c) closest to p, as barycentric coordinates (Ericson, Real-Time
// Collision Detection, 5.1.5).
Eigen::Vector3d closest_point_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

// The face of a mesh closest to a point, for many points that lie on the surface (a spot's centre,
// the vertices of a refinement of the same surface): every face is filed in the cells of a uniform
// grid that its bounding box overlaps, so a point on a face finds that face among the few filed in
// its own cell. A point whose cell holds no face (off the surface) is answered by trying every face.
class FaceLocator {
 public:
  explicit FaceLocator(const InputMesh& mesh);
  SurfacePoint locate(const Eigen::Vector3d& p) const;

 private:
  std::int64_t cell_key(const Eigen::Vector3d& p) const;
  // The closest of `faces` to p (squared distance in `best`), updating `found`.
  void closest_of(const std::vector<int>& faces, const Eigen::Vector3d& p, SurfacePoint& found, double& best) const;

  const InputMesh& mesh_;
  Eigen::Vector3d origin_;
  double cell_ = 1.0;
  std::vector<int> all_faces_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

}  // namespace physarum
