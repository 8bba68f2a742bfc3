#include "common/harness/smoothing_spectrum.hpp"

#include "common/base/errors.hpp"

namespace physarum {
namespace {

constexpr double kPi = 3.14159265358979323846;

double mass_norm2(const SurfaceDomain& domain, const Eigen::VectorXd& x) {
  double energy = 0.0;
  for (int i = 0; i < domain.vertex_count; ++i) energy += domain.vertex_mass[static_cast<size_t>(i)] * x[i] * x[i];
  return energy;
}

}  // namespace

SmoothingSpectrum::SmoothingSpectrum(const SurfaceDomain& domain, std::vector<double> scales)
    : domain_(domain), scales_(std::move(scales)) {
  const Eigen::SparseMatrix<double> L = domain_.laplacian.to_eigen();
  for (double scale : scales_) {
    const double t = (scale / (2.0 * kPi)) * (scale / (2.0 * kPi));
    Eigen::SparseMatrix<double> S = t * L;
    for (int i = 0; i < domain_.vertex_count; ++i) S.coeffRef(i, i) += domain_.vertex_mass[static_cast<size_t>(i)];
    auto solver = std::make_shared<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(S);
    if (solver->info() != Eigen::Success) throw InputError("compare: cannot factorise the diffusion smoother");
    smoothers_.push_back(solver);
  }
}

SmoothingSpectrum::Powers SmoothingSpectrum::of(const Eigen::VectorXd& u, double normaliser) const {
  Powers p;
  Eigen::VectorXd mu(domain_.vertex_count);
  for (int i = 0; i < domain_.vertex_count; ++i) mu[i] = domain_.vertex_mass[static_cast<size_t>(i)] * u[i];
  const bool zero = !(normaliser > 0.0);
  Eigen::VectorXd previous;
  for (size_t k = 0; k < smoothers_.size(); ++k) {
    Eigen::VectorXd smooth = smoothers_[k]->solve(mu);
    p.detail.push_back(zero ? 0.0 : mass_norm2(domain_, u - smooth) / normaliser);
    if (k > 0) p.band.push_back(zero ? 0.0 : mass_norm2(domain_, previous - smooth) / normaliser);
    previous = std::move(smooth);
  }
  return p;
}

}  // namespace physarum
