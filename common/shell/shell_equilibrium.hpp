#pragma once
// Static equilibrium of the sheet for a given rest state: the positions where the elastic energy's
// gradient vanishes, found by Newton's method from the current shape.
//
// - Each iteration solves H d = -g, factored by CHOLMOD through SharedCholesky (one symbolic analysis
//   per topology). H is the exact Hessian where that is positive definite (quadratic convergence near
//   a stable equilibrium); otherwise the sum of the element Hessians made positive semidefinite
//   (common/numerics/positive_projection.hpp), so d descends even where the sheet is compressed and
//   about to buckle. A factorization is reused (a chord step) while its steps keep cutting the
//   residual by 4 or more, down to 1e-7; below that every step is a full Newton step again.
// - Rigid motions are removed by a gauge: three vertices of one face ("gauge face") lose six
//   coordinates: its first vertex all three, its second the two across the first edge, its third
//   the one out of the face's plane —, which leaves the energy's minimisers unchanged up to a rigid
//   motion and makes H positive definite.
// - A backtracking line search (Armijo) on the energy, which after a full projected step tries
//   longer ones (a buckling mode's curvature is overstated by the projection); a step whose energy
//   change is lost in rounding is accepted when it lowers the residual instead.
// - The residual is the largest force on a free coordinate divided by Y h l, with l the mean rest
//   edge length: a dimensionless strain, so one tolerance serves every sheet size and material.
#include "common/numerics/shared_cholesky.hpp"
#include "common/shell/shell_energy.hpp"

#include <array>
#include <memory>
#include <vector>

namespace physarum {

struct NewtonSettings {
  int max_iterations = 200;
  double tolerance = 1e-10;  // on the residual
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;             // Newton steps taken
  int projected_iterations = 0;   // steps that used the projected Hessian
  int factorizations = 0;         // Cholesky factorizations, failed ones included
  std::vector<double> residuals;  // before each step, and the final one
  ShellEnergyParts energy;        // at the final positions
  double residual() const { return residuals.empty() ? 0.0 : residuals.back(); }
};

class ShellEquilibrium {
 public:
  // `gauge_face`: the face whose vertices carry the six fixed coordinates (see above); a face near
  // the middle of the sheet keeps the rest free to move symmetrically.
  ShellEquilibrium(const ShellTopology& topology, const ShellMaterial& material, int gauge_face);
  ~ShellEquilibrium();

  // Moves `positions` to equilibrium for `rest`. On return they are the last iterate (the
  // equilibrium when report.converged; a lower-energy shape otherwise).
  NewtonReport solve(std::vector<Eigen::Vector3d>& positions, const ShellRestState& rest,
                     const NewtonSettings& settings) const;

  const ShellEnergy& energy() const { return energy_; }

 private:
  // Assembles and factors the Newton matrix at x (the fixed coordinates' rows replaced by identity);
  // returns the factor's index in cholesky_.
  // With `try_exact`, the exact Hessian first; `projected`: whether the projected one was used.
  // Counts the factorizations and projected iterations into `report`.
  int factor_hessian(const Eigen::VectorXd& x, const ShellRestState& rest, const std::array<int, 6>& fixed,
                     Eigen::SparseMatrix<double>& h, bool try_exact, bool& projected, NewtonReport& report) const;

  ShellEnergy energy_;
  int gauge_face_;
  std::unique_ptr<SharedCholesky> cholesky_;
};

// The face whose centroid lies nearest the mean of the vertices.
int central_face(const ShellTopology& topology, const std::vector<Eigen::Vector3d>& positions);

}  // namespace physarum
