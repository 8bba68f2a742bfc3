#pragma once
// The diffusion-decay field model in the serial reference (common/model/diffusion_decay.hpp defines it):
// paper Eq. 1 discretised with the cotan Laplacian L and lumped mass M, with per-vertex rates R_dif,
// R_dec (Eq. 6 forward Euler with sub-steps under the stability limit, Eq. 7 backward Euler by a
// sparse factorisation made once). An optional write rate w (Sec. 3.3 write-stimuli, concentration
// per second per vertex) is a source term of the PDE, du/dt = ... + w: forward Euler adds h w in
// each sub-step, backward Euler solves A u' = M (u + dt w); with diffusion off both reach exactly
// u = w / r_dec. The concentration is clamped at zero after each sub-step (forward) or the solve
// (backward), so a negative rate removes pheromone but never makes it negative.
#include "common/model/diffusion_decay.hpp"
#include "common/base/element_data.hpp"
#include "common/model/diffusion_decay.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/model/vertex_parameters.hpp"
#include "reference/field_model.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>

namespace physarum {

class ReferenceDiffusionDecay final : public ReferenceFieldModel {
 public:
  // Reads domain.vertex_mass and domain.laplacian and the diffuse_rate / decay_rate parameters (one
  // per vertex). Backward Euler factorises its system here, once. The domain must outlive this.
  // Throws InputError when sizes disagree or time_step is not > 0.
  ReferenceDiffusionDecay(const SurfaceDomain& domain, const VertexParameters& params, Integrator integrator,
                          double time_step);

  // One time step with the step's deposits, in the order the integrator needs (deposit_order).
  void advance(IntrinsicVertexData<double>& u, const IntrinsicVertexData<double>& deposits) override;

  // One time step of diffusion and decay (and the write rate, when set; no deposits).
  void step(IntrinsicVertexData<double>& u);
  // The write rate per vertex (finite; InputError naming the vertex otherwise), or empty for none.
  void set_write_rate(const IntrinsicVertexData<double>& rate);
  const IntrinsicVertexData<double>& write_rate() const { return write_rate_; }
  // An AMOUNT at a vertex raises its concentration by amount / vertex_mass.
  void add_deposits(IntrinsicVertexData<double>& u, const IntrinsicVertexData<double>& amount_per_vertex) const;

  double time_step() const { return time_step_; }
  Integrator integrator() const { return integrator_; }
  // Forward Euler: the largest sub-step this model takes (common/model/diffusion_decay.hpp has the bound),
  // and how many sub-steps one step takes (1 when time_step is within the bound). Backward Euler: 1.
  double stable_time_step() const { return stable_time_step_; }
  int sub_steps() const { return sub_steps_; }

  // Total amount sum_i m_i u_i (conserved by diffusion with a uniform diffuse rate).
  double total_amount(const IntrinsicVertexData<double>& u) const;
  int vertex_count() const { return static_cast<int>(inverse_mass_.size()); }

 private:
  void check_size(const IntrinsicVertexData<double>& values, const char* what) const;
  void forward_sub_step(IntrinsicVertexData<double>& u, double h);
  void backward_step(IntrinsicVertexData<double>& u);

  const SurfaceDomain& domain_;
  Integrator integrator_;
  double time_step_;
  IntrinsicVertexData<double> scratch_;
  IntrinsicVertexData<double> inverse_mass_;
  IntrinsicVertexData<double> diffuse_over_mass_;  // r_dif,i / m_i
  IntrinsicVertexData<double> decay_rate_;         // r_dec,i
  IntrinsicVertexData<double> write_rate_;         // w_i, empty: no source term
  double stable_time_step_ = 0.0;
  int sub_steps_ = 1;
  double sub_step_ = 0.0;

  // Backward Euler: A = M + dt (R_dif L + R_dec M), factorised once.
  bool symmetric_ = true;
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> ldlt_;
  std::unique_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>>> lu_;
  Eigen::VectorXd rhs_, solution_;
  Eigen::VectorXd ldlt_diagonal_;  // D of the LDL^T factors (Eigen's vectorD() returns a copy)
};

}  // namespace physarum
