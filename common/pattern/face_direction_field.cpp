// Nearest-face lookup of a per-face direction field.
#include "common/pattern/face_direction_field.hpp"

#include "common/base/errors.hpp"
#include "common/mesh/closest_point.hpp"

#include <limits>
#include <string>

namespace physarum {

Eigen::Vector3d FaceDirectionField::at(const Eigen::Vector3d& point) const {
  if (mesh.triangles.empty() || directions.size() != mesh.triangles.size())
    throw InputError(mesh.source + ": the direction field has " + std::to_string(directions.size()) + " vectors for " +
                     std::to_string(mesh.triangles.size()) + " faces");
  double best = std::numeric_limits<double>::infinity();
  size_t best_face = 0;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const Eigen::Vector3d& a = mesh.positions[static_cast<size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.positions[static_cast<size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.positions[static_cast<size_t>(t[2])];
    const Eigen::Vector3d bary = closest_point_barycentric(point, a, b, c);
    const double d = (bary[0] * a + bary[1] * b + bary[2] * c - point).squaredNorm();
    if (d < best) {
      best = d;
      best_face = f;
    }
  }
  return directions[best_face];
}

}  // namespace physarum
