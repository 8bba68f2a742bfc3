#pragma once
// A point on a triangle mesh: a face and barycentric coordinates in it (non-negative, summing to 1).
#include <Eigen/Core>

namespace physarum {

struct SurfacePoint {
  int face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
};

}  // namespace physarum
