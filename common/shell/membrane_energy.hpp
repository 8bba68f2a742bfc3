#pragma once
// The membrane (stretching) energy of one triangle of the sheet: St. Venant-Kirchhoff in plane
// stress, measured against the triangle's REST METRIC rather than a rest shape. Growth changes the
// rest metric face by face (common/shell/rest_metric.hpp); neighbouring faces' rest metrics need not
// fit together in the plane, and the sheet must bend to accommodate them.
//
// With e1 = x1 - x0, e2 = x2 - x0 the triangle's edge vectors, the deformed metric is
// a = [e1 e2]^T [e1 e2] (2 x 2) and the rest metric abar (same basis). The Green strain is
// E = (abar^-1 a - I) / 2, and the energy
//   W = Abar * Y h / (2 (1 - nu^2)) * ((1 - nu) tr(E^2) + nu tr(E)^2),   Abar = sqrt(det abar) / 2.
// W is quadratic in the entries of a and a is quadratic in the positions, so the gradient and the
// Hessian below are exact closed forms (checked against finite differences in the tests).
#include "common/shell/shell_material.hpp"

#include <Eigen/Core>

namespace physarum {

using Vector9d = Eigen::Matrix<double, 9, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;

// The metric [e1 e2]^T [e1 e2] of the triangle (x0, x1, x2).
Eigen::Matrix2d triangle_metric(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2);
// The area of a triangle with metric `metric`: sqrt(det) / 2.
double metric_area(const Eigen::Matrix2d& metric);

struct MembraneElement {
  double energy = 0.0;
  Vector9d gradient = Vector9d::Zero();  // d energy / d (x0, x1, x2)
  Matrix9d hessian = Matrix9d::Zero();   // exact, possibly indefinite (compression)
};

// The energy alone (line searches).
double membrane_energy(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                       const Eigen::Matrix2d& rest_metric, const ShellMaterial& material);

// Energy, gradient and (when `with_hessian`) Hessian.
MembraneElement membrane_element(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                 const Eigen::Matrix2d& rest_metric, const ShellMaterial& material,
                                 bool with_hessian);

}  // namespace physarum
