#pragma once
// Where a sketch window lies on the surface it drives (../shared/DESIGN.md, "Sketches"): the window
// [0, w] x [0, h] maps onto the input mesh's own x/y extent (a PNG as it is seen: its top row at the
// largest y), and the mesh is scaled to `area` m^2 as scale_to_area does. Converts window lengths
// and areas to metres and back, and input points to window points.
#include "common/mesh/input_mesh.hpp"
#include "common/sketch/sketch.hpp"

#include <Eigen/Core>

namespace physarum::cli {

struct SketchPatch {
  Eigen::Vector2d window = Eigen::Vector2d::Ones();
  Eigen::Vector2d low = Eigen::Vector2d::Zero(), high = Eigen::Vector2d::Ones();  // the input's x/y extent
  double scale = 1.0;  // metres per input unit (sqrt(area / the input's area))

  // Metres per window unit along x and y.
  Eigen::Vector2d metres_per_unit() const;
  double area_in_metres(double window_area) const;
  double length_in_metres(double window_length) const;  // the mean of the two axes' scales
  Eigen::Vector2d window_point(const Eigen::Vector3d& input_point) const;
};

// InputError when the mesh has no extent in x or y (a patch seen edge-on), or area <= 0.
SketchPatch sketch_patch(const Sketch& sketch, const InputMesh& mesh, double area);

}  // namespace physarum::cli
