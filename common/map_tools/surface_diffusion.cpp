#include "common/map_tools/surface_diffusion.hpp"

#include "common/base/errors.hpp"
#include "common/numerics/shared_cholesky.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace physarum {

BackwardEulerDiffusion::BackwardEulerDiffusion(const SurfaceDomain& domain, double step, const std::vector<int>* ordering) {
  if (!std::isfinite(step) || !(step > 0.0))
    throw InputError("diffusion: the step " + std::to_string(step) + " must be a positive finite time");
  const int n = domain.vertex_count;
  mass_ = Eigen::Map<const Eigen::VectorXd>(domain.vertex_mass.data(), n);
  // Column-major for the Cholesky factorization; L is symmetric, so transposing the CSR is free.
  Eigen::SparseMatrix<double> system = Eigen::SparseMatrix<double>(domain.laplacian.to_eigen()) * step;
  for (int i = 0; i < n; ++i) system.coeffRef(i, i) += mass_[i];
  solver_ = std::make_shared<SharedCholesky>(system, ordering);
  try {
    solver_->factor(system, "the backward-Euler matrix");
  } catch (const std::runtime_error&) {
    throw InputError("diffusion: the backward-Euler matrix M + h L (h = " + std::to_string(step) +
                     ") could not be factorized (a vertex without area?)");
  }
}

IntrinsicVertexData<double> BackwardEulerDiffusion::step(const IntrinsicVertexData<double>& u) const {
  const Eigen::VectorXd rhs = mass_.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(u.data(), mass_.size()));
  const Eigen::VectorXd next = solver_->solve(0, rhs);
  return IntrinsicVertexData<double>(std::vector<double>(next.data(), next.data() + next.size()));
}

IntrinsicVertexData<double> diffuse_on_surface(const SurfaceDomain& domain, const IntrinsicVertexData<double>& u,
                                               double time, int steps, const std::vector<int>* ordering) {
  if (!std::isfinite(time) || !(time > 0.0))
    throw InputError("diffusion: \"time\" = " + std::to_string(time) + " must be a positive finite time");
  if (steps < 1) throw InputError("diffusion: \"steps\" = " + std::to_string(steps) + " must be at least 1");
  if (static_cast<int>(u.size()) != domain.vertex_count)
    throw InputError("diffusion: the map has " + std::to_string(u.size()) + " values for " +
                     std::to_string(domain.vertex_count) + " intrinsic vertices");
  const BackwardEulerDiffusion diffusion(domain, time / steps, ordering);
  IntrinsicVertexData<double> out = u;
  for (int k = 0; k < steps; ++k) out = diffusion.step(out);
  return out;
}

}  // namespace physarum
