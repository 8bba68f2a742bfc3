#include "reference/reaction_diffusion.hpp"

#include "common/base/errors.hpp"
#include "common/simulation/simulation_state.hpp"

#include <Eigen/SparseCholesky>

#include <cmath>
#include <limits>
#include <string>

namespace physarum {
namespace {

const char* const kWho = "reaction-diffusion";

}  // namespace

ReferenceReactionDiffusion::ReferenceReactionDiffusion(ReactionDiffusionSystem system)
    : system_(std::move(system)), layers_(system_.initial, static_cast<int>(system_.mass.size()), kWho) {
  const ReactionDiffusionSystem& s = system_;
  const size_t count = s.morphogens.size();
  vertex_count_ = static_cast<int>(s.mass.size());
  const size_t n = s.mass.size();
  check_reaction_diffusion_system(s, vertex_count_, kWho);

  std::vector<std::string> names = s.morphogens;
  names.insert(names.end(), s.coefficient_names.begin(), s.coefficient_names.end());
  point_.assign(names.size(), 0.0);
  std::vector<double*> addresses;
  for (double& x : point_) addresses.push_back(&x);
  for (size_t m = 0; m < count; ++m) {
    formulas_.emplace_back(s.reaction[m], names, std::string(kWho) + ": reaction." + s.morphogens[m]);
    formulas_.back().bind(addresses);
  }
  reaction_.assign(count, std::vector<double>(n, 0.0));
  diffused_.assign(n, 0.0);
  if (s.integrator == Integrator::Imex) factor_implicit_systems();
}

void ReferenceReactionDiffusion::factor_implicit_systems() {
  const ReactionDiffusionSystem& s = system_;
  const double dt = s.time_step;
  reduced_index_.assign(static_cast<size_t>(vertex_count_), -1);
  for (int v = 0; v < vertex_count_; ++v)
    if (!is_fixed(static_cast<size_t>(v))) {
      reduced_index_[static_cast<size_t>(v)] = static_cast<int>(free_vertices_.size());
      free_vertices_.push_back(v);
    }
  const int free_count = static_cast<int>(free_vertices_.size());
  for (size_t m = 0; m < s.morphogens.size(); ++m) {
    const CsrMatrix& k = s.stiffness[m];
    std::vector<Eigen::Triplet<double>> inner, outer;
    for (int f = 0; f < free_count; ++f) {
      const int row = free_vertices_[static_cast<size_t>(f)];
      inner.emplace_back(f, f, s.mass[static_cast<size_t>(row)]);
      for (int e = k.row_start[static_cast<size_t>(row)]; e < k.row_start[static_cast<size_t>(row) + 1]; ++e) {
        const int col = k.column[static_cast<size_t>(e)];
        const double a = dt * k.value[static_cast<size_t>(e)];
        const int reduced = reduced_index_[static_cast<size_t>(col)];
        if (reduced >= 0) inner.emplace_back(f, reduced, a);
        else outer.emplace_back(f, col, a);
      }
    }
    Eigen::SparseMatrix<double> a(free_count, free_count);
    a.setFromTriplets(inner.begin(), inner.end());
    auto factor = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(a);
    if (factor->info() != Eigen::Success)
      throw InputError(std::string(kWho) + ": the implicit diffusion system of '" + s.morphogens[m] + "' could not be factored");
    factor_.push_back(std::move(factor));
    Eigen::SparseMatrix<double, Eigen::RowMajor> c(free_count, vertex_count_);
    c.setFromTriplets(outer.begin(), outer.end());
    coupling_.push_back(std::move(c));
  }
}

void ReferenceReactionDiffusion::evaluate_reaction() {
  const size_t count = formulas_.size();
  const size_t coefficients = system_.coefficients.size();
  for (size_t v = 0; v < static_cast<size_t>(vertex_count_); ++v) {
    for (size_t m = 0; m < count; ++m) point_[m] = layers_[m][v];
    for (size_t c = 0; c < coefficients; ++c) point_[count + c] = system_.coefficients[c][v];
    for (size_t m = 0; m < count; ++m) reaction_[m][v] = formulas_[m].evaluate_bound();
  }
}

void ReferenceReactionDiffusion::explicit_substep(double h) {
  evaluate_reaction();
  for (size_t m = 0; m < formulas_.size(); ++m) {
    system_.stiffness[m].multiply(layers_[m].values(), diffused_);
    std::vector<double>& u = layers_[m].values();
    for (size_t v = 0; v < u.size(); ++v)
      if (!is_fixed(v)) u[v] += h * (reaction_[m][v] - diffused_[v] / system_.mass[v]);
    apply_floor(m);
  }
}

void ReferenceReactionDiffusion::imex_step(double dt) {
  evaluate_reaction();
  const int free_count = static_cast<int>(free_vertices_.size());
  Eigen::VectorXd rhs(free_count);
  for (size_t m = 0; m < formulas_.size(); ++m) {
    std::vector<double>& u = layers_[m].values();
    for (int f = 0; f < free_count; ++f) {
      const size_t v = static_cast<size_t>(free_vertices_[static_cast<size_t>(f)]);
      rhs[f] = system_.mass[v] * (u[v] + dt * reaction_[m][v]);
    }
    if (coupling_[m].nonZeros() > 0) rhs -= coupling_[m] * Eigen::Map<const Eigen::VectorXd>(u.data(), vertex_count_);
    const Eigen::VectorXd next = factor_[m]->solve(rhs);
    for (int f = 0; f < free_count; ++f) u[static_cast<size_t>(free_vertices_[static_cast<size_t>(f)])] = next[f];
    apply_floor(m);
  }
}

void ReferenceReactionDiffusion::apply_floor(size_t m) {
  if (system_.minimum.empty() || system_.minimum[m] == -std::numeric_limits<double>::infinity()) return;
  const double floor = system_.minimum[m];
  std::vector<double>& u = layers_[m].values();
  // A comparison, not std::max: a NaN stays NaN, so a diverging run is still seen as one.
  for (size_t v = 0; v < u.size(); ++v)
    if (!is_fixed(v) && u[v] < floor) u[v] = floor;
}

void ReferenceReactionDiffusion::step() {
  if (system_.integrator == Integrator::Imex) {
    imex_step(system_.time_step);
  } else {
    const double h = system_.time_step / system_.substeps;
    for (int s = 0; s < system_.substeps; ++s) explicit_substep(h);
  }
  ++steps_taken_;
  time_ = static_cast<double>(steps_taken_) * system_.time_step;
}

FieldStatistics ReferenceReactionDiffusion::field_statistics(double U, int layer) const {
  return compute_field_statistics(layers_.checked(layer, "field_statistics"), system_.mass, U);
}

SimulationState ReferenceReactionDiffusion::save_state() const {
  SimulationState state;
  state.steps_taken = steps_taken_;
  state.time = time_;
  state.layers = layers_.all();
  return state;
}

void ReferenceReactionDiffusion::restore_state(const SimulationState& state) {
  check_state_fits(state, layer_count(), vertex_count_, 0, 0, "reaction-diffusion");
  layers_.copy_from(state.layers);
  steps_taken_ = state.steps_taken;
  time_ = state.time;
}

}  // namespace physarum
