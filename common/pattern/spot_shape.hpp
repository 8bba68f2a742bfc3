#pragma once
// The shape of one segmented spot (common/pattern/pattern_segmentation.hpp) in its own tangent frame: where
// it is, how elongated and which way it points.
//   centre       the point of the surface (on the spot's triangles) closest to the area-weighted
//                mean of the clipped area: on a curved surface the mean itself lies off the surface;
//   frame        normal = the area-weighted mean of the clipped triangles' normals; tangent u = the
//                input x axis projected into the tangent plane (the y axis where x is within ~25
//                degrees of the normal), v = normal x u, so angles on a flat z = 0 surface are the
//                usual ones from +x toward +y;
//   second moment the covariance of the clipped area, projected into the tangent plane (local PCA):
//                eigenvalues l1 >= l2. aspect_ratio = sqrt(l1 / l2) (a/b for an ellipse with semi-axes
//                a, b: its variances are a^2/4 and b^2/4); the equivalent ellipse's axes are
//                4 sqrt(l1) and 4 sqrt(l2) (diameters); orientation = the angle of the major axis from
//                u, in [0, 180) degrees.
// Against a direction field (a vector at the centre), the angle between the major axis (a line, not
// an arrow) and the direction projected into the tangent plane, in [0, 90] degrees.
#include "common/mesh/input_mesh.hpp"
#include "common/pattern/pattern_segmentation.hpp"

#include <Eigen/Core>
#include <optional>

namespace physarum {

struct SpotShape {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // on the surface
  int centre_face = -1;                              // the triangle it lies in
  Eigen::Vector3d centre_barycentric = Eigen::Vector3d::Zero();
  int centre_vertex = -1;  // the corner of centre_face nearest the centre (where geodesics start)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(), tangent_u = Eigen::Vector3d::UnitX(),
                  tangent_v = Eigen::Vector3d::UnitY();
  Eigen::Vector3d major_axis = Eigen::Vector3d::UnitX();  // unit, in the tangent plane
  double major_length = 0.0, minor_length = 0.0;          // equivalent ellipse diameters 4 sqrt(l)
  double aspect_ratio = 1.0;
  double orientation_deg = 0.0;  // major axis from tangent_u toward tangent_v, [0, 180)
};

// The region must have positive area.
SpotShape spot_shape(const InputMesh& mesh, const PatternRegion& region);

// The angle between the spot's major axis and `direction` projected into its tangent plane, [0, 90]
// degrees; nothing when the direction is (nearly) normal to the surface there or zero.
std::optional<double> angle_to_direction_deg(const SpotShape& spot, const Eigen::Vector3d& direction);

}  // namespace physarum
