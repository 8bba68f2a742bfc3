#include "common/surface/eigenvalues.hpp"

#include "common/base/errors.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/SparseCholesky>
#include <Spectra/SymEigsShiftSolver.h>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace physarum {

namespace {

// Spectra's shift-and-invert operator for the symmetric matrix A = M^-1/2 L M^-1/2: y = (A - sigma I)^-1 x
// through a sparse LDL^T factorisation. With sigma below zero, A - sigma I is positive definite
// (A is positive semi-definite), so the factorisation needs no pivoting and the smallest
// eigenvalues of A become the largest of the inverse, where Lanczos converges in a few iterations.
class ShiftedInverse {
 public:
  using Scalar = double;

  explicit ShiftedInverse(Eigen::SparseMatrix<double> a) : a_(std::move(a)) {}
  Eigen::Index rows() const { return a_.rows(); }
  Eigen::Index cols() const { return a_.cols(); }

  void set_shift(double sigma) {
    Eigen::SparseMatrix<double> identity(a_.rows(), a_.cols());
    identity.setIdentity();
    solver_.compute(a_ - sigma * identity);
    if (solver_.info() != Eigen::Success)
      throw InputError("eigenvalues: factorising the shifted Laplacian failed (is the mesh valid?)");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, a_.rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, a_.rows());
    y = solver_.solve(x);
  }

 private:
  Eigen::SparseMatrix<double> a_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

}  // namespace

Eigenpairs smallest_eigenpairs(const CsrMatrix& laplacian, const IntrinsicVertexData<double>& mass, int count,
                               bool want_vectors) {
  const int n = laplacian.rows;
  if (laplacian.cols != n || static_cast<int>(mass.size()) != n)
    throw InputError("eigenvalues: Laplacian is " + std::to_string(laplacian.rows) + "x" + std::to_string(laplacian.cols) +
                     " but the mass has " + std::to_string(mass.size()) + " entries");
  for (int i = 0; i < n; ++i)
    if (!(mass[i] > 0.0) || !std::isfinite(mass[i]))
      throw InputError("eigenvalues: vertex " + std::to_string(i) + " has mass " + std::to_string(mass[i]) +
                       " (an isolated vertex, or a degenerate mesh)");
  count = std::min(count, n - 1);
  Eigenpairs out;
  if (count <= 0) return out;

  // Symmetric standard form: A = M^-1/2 L M^-1/2 has the same eigenvalues; x = M^-1/2 y.
  Eigen::VectorXd inv_sqrt_mass(n);
  for (int i = 0; i < n; ++i) inv_sqrt_mass[i] = 1.0 / std::sqrt(mass[i]);
  Eigen::SparseMatrix<double> a(laplacian.to_eigen());
  a = inv_sqrt_mass.asDiagonal() * a * inv_sqrt_mass.asDiagonal();

  // A shift a little below zero, relative to the matrix's scale, keeps A - sigma I definite while
  // leaving the zero eigenvalue well separated in the inverted spectrum.
  double scale = 0.0;
  for (int i = 0; i < n; ++i) scale = std::max(scale, a.coeff(i, i));
  const double sigma = -1e-8 * std::max(scale, 1e-300);

  ShiftedInverse op(std::move(a));
  // A few more eigenpairs than asked: a Krylov method can converge to the next eigenvalue before the
  // last copy of a repeated one (the unit sphere's fifth l = 2 pair when 9 are asked), and a copy
  // missed inside the wanted range shows up once the range ends beyond it. The extra ones are dropped.
  const int wanted = std::min(n - 1, count + std::max(10, count / 10));
  const int ncv = std::min(n, std::max(2 * wanted + 1, wanted + 20));
  Spectra::SymEigsShiftSolver<ShiftedInverse> solver(op, wanted, ncv, sigma);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12, Spectra::SortRule::SmallestAlge);
  if (solver.info() != Spectra::CompInfo::Successful)
    throw InputError("eigenvalues: the eigensolver did not converge for the " + std::to_string(count) +
                     " smallest eigenvalues");

  out.values = solver.eigenvalues().head(count);  // ascending (SmallestAlge)
  if (want_vectors) {
    // y^T y = 1  =>  x^T M x = 1
    out.vectors = inv_sqrt_mass.asDiagonal() * solver.eigenvectors().leftCols(count);
  }
  return out;
}

std::vector<double> smallest_eigenvalues(const CsrMatrix& laplacian, const IntrinsicVertexData<double>& mass, int count) {
  const Eigenpairs pairs = smallest_eigenpairs(laplacian, mass, count, false);
  return {pairs.values.data(), pairs.values.data() + pairs.values.size()};
}

std::vector<double> smallest_eigenvalues(const SurfaceDomain& domain, int count) {
  return smallest_eigenvalues(domain.laplacian, domain.vertex_mass, count);
}

Eigenpairs smallest_eigenpairs(const SurfaceDomain& domain, int count, bool want_vectors) {
  return smallest_eigenpairs(domain.laplacian, domain.vertex_mass, count, want_vectors);
}

}  // namespace physarum
