#pragma once
// The bending energy of one interior edge of the sheet: the discrete hinge of Grinspun et al.
// ("Discrete Shells", 2003). The hinge is the edge (x0, x1) with the triangles (x0, x1, x2) and
// (x1, x0, x3) on either side (both counter-clockwise); theta is its signed dihedral angle (0 when
// flat; negative when both wings fold towards the first triangle's normal), and
//   W = (D / 2) * |ebar|^2 / (Abar_1 + Abar_2) * (theta - theta_bar)^2
// with D the flexural rigidity, |ebar| the edge's rest length and Abar_i the rest areas of the two
// triangles. The factor is calibrated so that an equilateral mesh bent into a cylinder of radius R
// costs the plate energy (D / 2) / R^2 per unit area, whatever the edges' orientation; on such a mesh
// a general bend costs (D / 2) (k1^2 + k2^2 + 2 nu k1 k2) with nu = 1/3 (the hinge model's own
// Poisson coupling: the material's nu acts on the membrane only). Irregular meshes deviate by their
// triangles' shapes (about 17 % on the built-in disk's rings).
//
// The gradient of theta is the classical closed form (Bridson et al. 2003): the wings' opposite
// vertices move along their faces' normals by -1/height, the edge's ends share the opposite terms
// by where the opposite vertices project onto the edge. Its Hessian is that formula differentiated
// by forward-mode automatic differentiation (Eigen's AutoDiffScalar, 12 directions): exact, and
// checked against finite differences in the tests.
#include <Eigen/Core>

namespace physarum {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

// theta of the hinge (x0, x1; x2, x3), in (-pi, pi].
double dihedral_angle(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                      const Eigen::Vector3d& x3);

struct HingeElement {
  double energy = 0.0;
  Vector12d gradient = Vector12d::Zero();  // d energy / d (x0, x1, x2, x3)
  Matrix12d hessian = Matrix12d::Zero();   // exact, possibly indefinite
};

// k (theta - rest_angle)^2, with k = (D / 2) |ebar|^2 / (Abar_1 + Abar_2) precomputed by the caller.
double hinge_energy(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                    const Eigen::Vector3d& x3, double stiffness, double rest_angle);

HingeElement hinge_element(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                           const Eigen::Vector3d& x3, double stiffness, double rest_angle, bool with_hessian);

}  // namespace physarum
