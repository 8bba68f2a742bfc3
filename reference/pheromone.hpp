#pragma once
// The pheromone field of the serial reference: one concentration per intrinsic vertex, advanced by
// the diffusion-decay PDE (paper Eq. 1) discretised with the cotan Laplacian L and lumped mass M,
// with per-vertex rates R_dif, R_dec (Eq. 6 forward Euler, Eq. 7 backward Euler).
#include "common/scene.hpp"
#include "common/surface_domain.hpp"
#include "common/vertex_parameters.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

namespace physarum {

class ReferencePheromone {
 public:
  // Reads domain.vertex_mass and domain.laplacian and params.diffuse_rate / params.decay_rate (one
  // per vertex). Backward Euler factorises its system here, once. The domain must outlive this.
  // Throws InputError when sizes disagree or time_step is not > 0.
  ReferencePheromone(const SurfaceDomain& domain, const VertexParameters& params, Integrator integrator,
                     double time_step);

  // ---- the field ----
  const std::vector<double>& concentration() const { return u_; }
  void set_concentration(const std::vector<double>& u);  // size must be vertex_count
  void fill(double value);

  // ---- deposits: an AMOUNT at a vertex raises its concentration by amount / vertex_mass ----
  void add_deposit(int vertex, double amount) { u_[static_cast<size_t>(vertex)] += amount * inverse_mass_[static_cast<size_t>(vertex)]; }
  void add_deposits(const std::vector<double>& amount_per_vertex);

  // ---- time ----
  // Advances the field by one time step (diffusion and decay only; deposits are separate).
  void step();
  double time_step() const { return time_step_; }
  Integrator integrator() const { return integrator_; }
  // Forward Euler: the largest sub-step this field takes (see pheromone.cpp for the bound), and how
  // many sub-steps one step() takes (1 when time_step is within the bound). Backward Euler: 1.
  double stable_time_step() const { return stable_time_step_; }
  int sub_steps() const { return sub_steps_; }

  // Total amount sum_i m_i u_i (conserved by diffusion with a uniform diffuse rate).
  double total_amount() const;
  int vertex_count() const { return static_cast<int>(u_.size()); }

 private:
  void forward_sub_step(double h);
  void backward_step();

  const SurfaceDomain& domain_;
  Integrator integrator_;
  double time_step_;
  std::vector<double> u_, scratch_;
  std::vector<double> inverse_mass_;
  std::vector<double> diffuse_over_mass_;  // r_dif,i / m_i
  std::vector<double> decay_rate_;         // r_dec,i
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
