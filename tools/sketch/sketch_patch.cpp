#include "tools/sketch/sketch_patch.hpp"

#include "common/base/errors.hpp"
#include "common/base/value_range.hpp"

#include <cmath>

namespace physarum::cli {

Eigen::Vector2d SketchPatch::metres_per_unit() const {
  return (high - low).cwiseQuotient(window) * scale;
}

double SketchPatch::area_in_metres(double window_area) const {
  const Eigen::Vector2d m = metres_per_unit();
  return window_area * m.x() * m.y();
}

double SketchPatch::length_in_metres(double window_length) const {
  const Eigen::Vector2d m = metres_per_unit();
  return window_length * std::sqrt(m.x() * m.y());
}

Eigen::Vector2d SketchPatch::window_point(const Eigen::Vector3d& p) const {
  return (p.head<2>() - low).cwiseQuotient(high - low).cwiseProduct(window);
}

SketchPatch sketch_patch(const Sketch& sketch, const InputMesh& mesh, double area) {
  if (!(area > 0.0) || !std::isfinite(area))
    throw InputError("--area " + ValueRange::number(area) + ": the surface's area must be > 0 m^2");
  SketchPatch patch;
  patch.window = sketch.window;
  patch.low = patch.high = mesh.positions.front().head<2>();
  for (const Eigen::Vector3d& p : mesh.positions) {
    patch.low = patch.low.cwiseMin(p.head<2>());
    patch.high = patch.high.cwiseMax(p.head<2>());
  }
  if (!((patch.high - patch.low).minCoeff() > 0.0))
    throw InputError(mesh.source + ": has no extent in x or y; a sketch window maps onto the mesh's x/y extent");
  const double input_area = compute_statistics(mesh).area;
  patch.scale = std::sqrt(area / input_area);
  return patch;
}

}  // namespace physarum::cli
