#include "reference/diffusion_decay.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace physarum {

ReferenceDiffusionDecay::ReferenceDiffusionDecay(const SurfaceDomain& domain, const VertexParameters& params,
                                                 Integrator integrator, double time_step)
    : domain_(domain), integrator_(integrator), time_step_(time_step) {
  const int n = domain.vertex_count;
  const size_t un = static_cast<size_t>(n);
  if (!(time_step > 0.0) || !std::isfinite(time_step))
    throw InputError("pheromone: time step " + std::to_string(time_step) + " must be > 0");
  if (domain.vertex_mass.size() != un || domain.laplacian.rows != n || domain.laplacian.cols != n)
    throw InputError("pheromone: the surface domain's mass (" + std::to_string(domain.vertex_mass.size()) +
                     ") or Laplacian (" + std::to_string(domain.laplacian.rows) + ") size differs from its " +
                     std::to_string(n) + " vertices");
  const IntrinsicVertexData<double>& diffuse_rate = params[Param::diffuse_rate];
  if (diffuse_rate.size() != un || params[Param::decay_rate].size() != un)
    throw InputError("pheromone: parameter maps have " + std::to_string(params[Param::decay_rate].size()) +
                     " values for " + std::to_string(n) + " vertices");

  scratch_.assign(un, 0.0);
  inverse_mass_.assign(un, 0.0);
  diffuse_over_mass_.assign(un, 0.0);
  decay_rate_ = params[Param::decay_rate];
  for (int i = 0; i < n; ++i) {
    const double m = domain.vertex_mass[i];
    if (!(m > 0.0)) throw InputError("pheromone: vertex " + std::to_string(i) + " has lumped mass " + std::to_string(m) + " (must be > 0)");
    if (!(diffuse_rate[i] >= 0.0) || !(decay_rate_[i] >= 0.0))
      throw InputError("pheromone: vertex " + std::to_string(i) + " has a negative diffuse or decay rate");
    inverse_mass_[i] = 1.0 / m;
    diffuse_over_mass_[i] = diffuse_rate[i] / m;
  }

  // Forward Euler step limit (common/model/diffusion_decay.hpp has the derivation).
  const CsrMatrix& L = domain.laplacian;
  stable_time_step_ = forward_euler_stable_step(L, diffuse_over_mass_, decay_rate_);

  if (integrator == Integrator::Forward) {
    sub_steps_ = forward_euler_sub_steps(time_step, stable_time_step_);
    sub_step_ = time_step / sub_steps_;
    return;
  }

  // Backward Euler: A = M + dt (R_dif L + R_dec M). Symmetric when R_dif is a multiple of the identity
  // (L is symmetric), then LDL^T; a varying R_dif makes R_dif L non-symmetric, then LU.
  sub_steps_ = 1;
  symmetric_ = is_uniform(diffuse_rate);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(L.value.size() + un);
  for (int i = 0; i < n; ++i) {
    const double m = domain.vertex_mass[i];
    triplets.emplace_back(i, i, m * (1.0 + time_step * decay_rate_[i]));
    for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k)
      triplets.emplace_back(i, L.column[k], time_step * diffuse_rate[i] * L.value[k]);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  A.makeCompressed();
  if (symmetric_) {
    ldlt_ = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(A);
    if (ldlt_->info() != Eigen::Success)
      throw InputError("pheromone: the backward-Euler system could not be factorised (LDLT)");
  } else {
    lu_ = std::make_unique<Eigen::SparseLU<Eigen::SparseMatrix<double>>>();
    lu_->analyzePattern(A);
    lu_->factorize(A);
    if (lu_->info() != Eigen::Success)
      throw InputError("pheromone: the backward-Euler system could not be factorised (LU): " + lu_->lastErrorMessage());
  }
  if (symmetric_) ldlt_diagonal_ = ldlt_->vectorD();
  rhs_.resize(n);
  solution_.resize(n);
}

void ReferenceDiffusionDecay::check_size(const IntrinsicVertexData<double>& values, const char* what) const {
  if (values.size() != inverse_mass_.size())
    throw InputError(std::string("pheromone: ") + what + " has " + std::to_string(values.size()) + " values for " +
                     std::to_string(inverse_mass_.size()) + " vertices");
}

void ReferenceDiffusionDecay::advance(IntrinsicVertexData<double>& u, const IntrinsicVertexData<double>& deposits) {
  if (deposit_order(integrator_) == DepositOrder::AfterTransport) {
    step(u);
    add_deposits(u, deposits);
  } else {
    add_deposits(u, deposits);
    step(u);
  }
}

void ReferenceDiffusionDecay::add_deposits(IntrinsicVertexData<double>& u,
                                           const IntrinsicVertexData<double>& amount_per_vertex) const {
  check_size(u, "the field");
  check_size(amount_per_vertex, "the deposit");
  for (size_t i = 0; i < u.size(); ++i) u[i] += amount_per_vertex[i] * inverse_mass_[i];
}

void ReferenceDiffusionDecay::set_write_rate(const IntrinsicVertexData<double>& rate) {
  if (!rate.empty()) {
    check_size(rate, "the write rate");
    for (size_t i = 0; i < rate.size(); ++i)
      if (!std::isfinite(rate[i]))
        throw InputError("pheromone: the write rate at vertex " + std::to_string(i) + " is " + std::to_string(rate[i]) +
                         " (must be finite)");
  }
  write_rate_ = rate;
}

void ReferenceDiffusionDecay::step(IntrinsicVertexData<double>& u) {
  check_size(u, "the field");
  if (integrator_ == Integrator::Backward) {
    backward_step(u);
  } else {
    for (int s = 0; s < sub_steps_; ++s) forward_sub_step(u, sub_step_);
  }
}

// Eq. 6 divided by M: u' = u - h (M^-1 R_dif L u + R_dec u), row by row through the CSR Laplacian.
void ReferenceDiffusionDecay::forward_sub_step(IntrinsicVertexData<double>& u, double h) {
  const CsrMatrix& L = domain_.laplacian;
  const int n = static_cast<int>(u.size());
  for (int i = 0; i < n; ++i) {
    double Lu = 0.0;
    for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) Lu += L.value[k] * u[L.column[k]];
    scratch_[i] = u[i] - h * (diffuse_over_mass_[i] * Lu + decay_rate_[i] * u[i]);
  }
  // The source term in its own pass, so the base model's arithmetic stays as it was.
  if (!write_rate_.empty())
    for (int i = 0; i < n; ++i) scratch_[i] = std::max(scratch_[i] + h * write_rate_[i], 0.0);
  u.values().swap(scratch_.values());
}

// Eq. 7: [M + dt (R_dif L + R_dec M)] u' = M u with the factorisation made in the constructor; the
// write rate joins the right-hand side as M (u + dt w).
void ReferenceDiffusionDecay::backward_step(IntrinsicVertexData<double>& u) {
  const int n = static_cast<int>(u.size());
  if (write_rate_.empty())
    for (int i = 0; i < n; ++i) rhs_[i] = domain_.vertex_mass[i] * u[i];
  else
    for (int i = 0; i < n; ++i) rhs_[i] = domain_.vertex_mass[i] * (u[i] + time_step_ * write_rate_[i]);
  if (symmetric_) {
    // P A P^-1 = L D L^T, solved step by step into the buffers sized in the constructor: Eigen's own
    // solve() permutes the result in place, which allocates a mask on every call.
    const Eigen::VectorXi& p = ldlt_->permutationP().indices();  // empty: no permutation
    const bool permuted = p.size() == n;
    for (int i = 0; i < n; ++i) solution_[permuted ? p[i] : i] = rhs_[i];  // solution = P rhs
    ldlt_->matrixL().solveInPlace(solution_);
    solution_.array() /= ldlt_diagonal_.array();
    ldlt_->matrixU().solveInPlace(solution_);
    for (int i = 0; i < n; ++i) u[i] = solution_[permuted ? p[i] : i];  // u = P^-1 solution
  } else {
    solution_ = lu_->solve(rhs_);
    for (int i = 0; i < n; ++i) u[i] = solution_[i];
  }
  if (!write_rate_.empty())
    for (int i = 0; i < n; ++i) u[i] = std::max(u[i], 0.0);
}

double ReferenceDiffusionDecay::total_amount(const IntrinsicVertexData<double>& u) const {
  check_size(u, "the field");
  double total = 0.0;
  for (size_t i = 0; i < u.size(); ++i) total += domain_.vertex_mass[i] * u[i];
  return total;
}

}  // namespace physarum
