#include "common/shell/shell_equilibrium.hpp"

#include "common/shell/membrane_energy.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace physarum {
namespace {

// A rotation and translation taking the gauge face to its canonical place: first vertex at the
// origin, second on +x, third in the xy-plane. In that frame the six fixed coordinates are plain
// coordinates: (x, y, z) of the first, (y, z) of the second, z of the third.
struct GaugeFrame {
  Eigen::Matrix3d rotation;  // rows: the frame's axes
  Eigen::Vector3d origin;

  GaugeFrame(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) : origin(a) {
    const Eigen::Vector3d ex = (b - a).normalized();
    const Eigen::Vector3d ez = ex.cross(c - a).normalized();
    rotation.row(0) = ex.transpose();
    rotation.row(1) = ez.cross(ex).transpose();
    rotation.row(2) = ez.transpose();
  }
  Eigen::VectorXd into(const std::vector<Eigen::Vector3d>& positions) const {
    Eigen::VectorXd x(3 * static_cast<Eigen::Index>(positions.size()));
    for (std::size_t v = 0; v < positions.size(); ++v)
      x.segment<3>(3 * static_cast<Eigen::Index>(v)) = rotation * (positions[v] - origin);
    return x;
  }
  std::vector<Eigen::Vector3d> out_of(const Eigen::VectorXd& x) const {
    std::vector<Eigen::Vector3d> positions(static_cast<std::size_t>(x.size() / 3));
    for (std::size_t v = 0; v < positions.size(); ++v)
      positions[v] = rotation.transpose() * x.segment<3>(3 * static_cast<Eigen::Index>(v)) + origin;
    return positions;
  }
};

double mean_rest_edge(const ShellRestState& rest) {
  double sum = 0.0;
  for (const Eigen::Matrix2d& m : rest.face_metric) sum += std::sqrt(m(0, 0)) + std::sqrt(m(1, 1));
  return rest.face_metric.empty() ? 1.0 : sum / (2.0 * static_cast<double>(rest.face_metric.size()));
}

// Replaces the fixed coordinates' rows and columns of `h` by the identity times `diagonal`. The
// pattern is symmetric, so a fixed coordinate's row entries are found through its column's: only
// those columns are visited, not the whole matrix.
void fix_coordinates(Eigen::SparseMatrix<double>& h, const std::array<int, 6>& fixed, double diagonal) {
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  double* values = h.valuePtr();
  for (int p : fixed)
    for (int k = outer[p]; k < outer[p + 1]; ++k) {
      const int row = inner[k];
      values[k] = row == p ? diagonal : 0.0;
      if (row == p) continue;
      const int* mirror = std::lower_bound(inner + outer[row], inner + outer[row + 1], p);
      values[mirror - inner] = 0.0;
    }
}

// Below this residual every step gets a fresh factorization (see solve()).
constexpr double kReuseBelow = 1e-7;

struct LineSearchResult {
  bool moved = false;      // false: no step lowered the energy or the forces
  bool full_step = false;  // the Newton step itself was accepted
  double step = 0.0;       // along the direction
  double energy = 0.0;     // there
};

// Backtracking (Armijo) along d from x; after an accepted full step of a projected Hessian, longer
// steps while they keep lowering the energy (along a buckling mode the projected Hessian overstates
// the curvature). Near the minimum the energy's change drowns in its rounding: when no step passes,
// the full step is taken if it brings the forces down.
template <typename Energy, typename Gradient>
LineSearchResult search_line(const Eigen::VectorXd& x, const Eigen::VectorXd& d, const Eigen::VectorXd& g, double energy,
                             bool projected, const Energy& energy_at, const Gradient& gradient_at) {
  const double slope = g.dot(d);
  LineSearchResult result;
  double step = 1.0;
  for (int halving = 0; halving < 40; ++halving, step *= 0.5) {
    const double trial = energy_at(x + step * d);
    if (trial <= energy + 1e-4 * step * slope) {
      result = {true, halving == 0, step, trial};
      break;
    }
  }
  if (!result.moved) {
    if (gradient_at(x + d).template lpNorm<Eigen::Infinity>() >= g.lpNorm<Eigen::Infinity>()) return result;
    return {true, true, 1.0, energy_at(x + d)};
  }
  if (projected && result.full_step)
    for (double longer = 2.0; longer <= 64.0; longer *= 2.0) {
      const double further = energy_at(x + longer * d);
      if (!(further < result.energy)) break;
      result.step = longer;
      result.energy = further;
    }
  return result;
}

}  // namespace

int ShellEquilibrium::factor_hessian(const Eigen::VectorXd& x, const ShellRestState& rest, const std::array<int, 6>& fixed,
                                     Eigen::SparseMatrix<double>& h, bool try_exact, bool& projected,
                                     NewtonReport& report) const {
  cholesky_->release_factors();
  projected = false;
  double diagonal = 0.0;
  // The exact Hessian when it is positive definite: quadratic convergence near a stable equilibrium.
  if (try_exact) {
    energy_.hessian(x, rest, false, h);
    diagonal = h.diagonal().cwiseAbs().maxCoeff();
    fix_coordinates(h, fixed, diagonal);
    ++report.factorizations;
    try {
      return cholesky_->factor(h, "the shell's Hessian");
    } catch (const std::runtime_error&) {
    }
  }
  // Otherwise (far from equilibrium, or a sheet about to buckle) the element Hessians made positive
  // semidefinite (common/numerics/positive_projection.hpp); a small shift, grown until CHOLMOD
  // accepts the matrix, covers what is left singular.
  projected = true;
  energy_.hessian(x, rest, true, h);
  diagonal = h.diagonal().cwiseAbs().maxCoeff();
  fix_coordinates(h, fixed, diagonal);
  ++report.projected_iterations;
  Eigen::VectorXd unshifted_diagonal;
  for (double shift = 0.0;; shift = shift == 0.0 ? 1e-12 * diagonal : shift * 100.0) {
    ++report.factorizations;
    if (shift > 0.0) {
      if (unshifted_diagonal.size() == 0) unshifted_diagonal = h.diagonal();
      for (int i = 0; i < h.rows(); ++i) h.coeffRef(i, i) = unshifted_diagonal(i) + shift;
    }
    try {
      return cholesky_->factor(h, "the shell's Hessian");
    } catch (const std::runtime_error&) {
      if (shift > diagonal) throw;
    }
  }
}

ShellEquilibrium::ShellEquilibrium(const ShellTopology& topology, const ShellMaterial& material, int gauge_face)
    : energy_(topology, material), gauge_face_(gauge_face) {
  if (gauge_face < 0 || gauge_face >= static_cast<int>(topology.faces.size()))
    throw std::invalid_argument("ShellEquilibrium: gauge face out of range");
  Eigen::SparseMatrix<double> spd = energy_.pattern();
  for (int i = 0; i < spd.rows(); ++i) spd.coeffRef(i, i) = 1.0;
  cholesky_ = std::make_unique<SharedCholesky>(spd);
}

ShellEquilibrium::~ShellEquilibrium() = default;

NewtonReport ShellEquilibrium::solve(std::vector<Eigen::Vector3d>& positions, const ShellRestState& rest,
                                     const NewtonSettings& settings) const {
  const auto& face = energy_.topology().faces[static_cast<std::size_t>(gauge_face_)];
  const GaugeFrame frame(positions[face[0]], positions[face[1]], positions[face[2]]);
  const std::array<int, 6> fixed = {3 * face[0], 3 * face[0] + 1, 3 * face[0] + 2,
                                    3 * face[1] + 1, 3 * face[1] + 2, 3 * face[2] + 2};
  Eigen::VectorXd x = frame.into(positions);
  const double force_scale = energy_.material().membrane_stiffness() * mean_rest_edge(rest);

  const auto free_gradient = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd g = energy_.gradient(at, rest);
    for (int i : fixed) g(i) = 0.0;
    return g;
  };
  NewtonReport report;
  Eigen::VectorXd g = free_gradient(x);
  double energy = energy_.energy(x, rest).total();
  Eigen::SparseMatrix<double> h;
  // Whether to try the exact Hessian first: a factorization that fails costs nearly as much as one
  // that succeeds, so after a failure only once the projected steps have become full Newton steps
  // (the iterate is closing in).
  bool try_exact = true, projected = false;
  int index = -1;
  for (;;) {
    report.residuals.push_back(g.lpNorm<Eigen::Infinity>() / force_scale);
    if (report.residuals.back() <= settings.tolerance) {
      report.converged = true;
      break;
    }
    if (report.iterations >= settings.max_iterations) break;
    // A factorization is reused while the steps it gives keep cutting the residual by 4 or more
    // (a chord step costs a solve, a factorization 10-20 of them); the last iterations, below
    // kReuseBelow, are full Newton steps again, which converge quadratically.
    const double residual = report.residuals.back();
    const bool reuse = index >= 0 && residual > kReuseBelow && report.residuals.size() >= 2 &&
                       residual <= 0.25 * report.residuals[report.residuals.size() - 2];
    if (!reuse) index = factor_hessian(x, rest, fixed, h, try_exact, projected, report);
    const Eigen::VectorXd d = -cholesky_->solve(index, g);
    const LineSearchResult found = search_line(
        x, d, g, energy, projected, [&](const Eigen::VectorXd& at) { return energy_.energy(at, rest).total(); },
        free_gradient);
    if (!found.moved) break;
    try_exact = !projected || found.full_step;
    x += found.step * d;
    g = free_gradient(x);
    energy = found.energy;
    ++report.iterations;
  }
  cholesky_->release_factors();
  report.energy = energy_.energy(x, rest);
  positions = frame.out_of(x);
  return report;
}

int central_face(const ShellTopology& topology, const std::vector<Eigen::Vector3d>& positions) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : positions) mean += p;
  mean /= static_cast<double>(std::max<std::size_t>(positions.size(), 1));
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int f = 0; f < static_cast<int>(topology.faces.size()); ++f) {
    const auto& t = topology.faces[static_cast<std::size_t>(f)];
    const double distance = ((positions[t[0]] + positions[t[1]] + positions[t[2]]) / 3.0 - mean).squaredNorm();
    if (distance < best_distance) best_distance = distance, best = f;
  }
  return best;
}

}  // namespace physarum
