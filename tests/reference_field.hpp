#pragma once
// One pheromone layer with its diffusion-decay model, for tests that advance a field alone: the
// simulation keeps layers and model apart (reference/field_model.hpp); a test of the PDE wants them
// together, as one object that steps its own values.
#include "common/base/element_data.hpp"
#include "common/base/errors.hpp"
#include "reference/diffusion_decay.hpp"

#include <string>

namespace physarum::testing {

class ReferenceField {
 public:
  ReferenceField(const SurfaceDomain& domain, const VertexParameters& params, Integrator integrator, double time_step)
      : model_(domain, params, integrator, time_step), u_(static_cast<size_t>(domain.vertex_count), 0.0) {}

  const IntrinsicVertexData<double>& concentration() const { return u_; }
  void set_concentration(const IntrinsicVertexData<double>& u) {
    if (u.size() != u_.size())
      throw InputError("test field: " + std::to_string(u.size()) + " values for " + std::to_string(u_.size()));
    u_ = u;
  }
  void fill(double value) { u_.assign(u_.size(), value); }
  void add_deposits(const IntrinsicVertexData<double>& amounts) { model_.add_deposits(u_, amounts); }
  void add_deposit(int vertex, double amount) {
    IntrinsicVertexData<double> amounts(u_.size(), 0.0);
    amounts[static_cast<size_t>(vertex)] = amount;
    add_deposits(amounts);
  }
  void step() { model_.step(u_); }
  double total_amount() const { return model_.total_amount(u_); }
  double stable_time_step() const { return model_.stable_time_step(); }
  int sub_steps() const { return model_.sub_steps(); }

 private:
  ReferenceDiffusionDecay model_;
  IntrinsicVertexData<double> u_;
};

}  // namespace physarum::testing
