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

[[noreturn]] void fail(const std::string& problem) { throw InputError(std::string(kWho) + ": " + problem); }

}  // namespace

ReferenceReactionDiffusion::ReferenceReactionDiffusion(ReactionDiffusionSystem system) : system_(std::move(system)) {
  const ReactionDiffusionSystem& s = system_;
  const size_t count = s.morphogens.size();
  vertex_count_ = static_cast<int>(s.mass.size());
  const size_t n = s.mass.size();
  if (count < 2 || count > 4) fail(std::to_string(count) + " morphogens; a system has 2 to 4");
  if (s.reaction.size() != count || s.stiffness.size() != count || s.initial.size() != count)
    fail("one reaction formula, stiffness matrix and initial layer per morphogen are needed");
  if (s.coefficients.size() != s.coefficient_names.size()) fail("one value array per coefficient name is needed");
  for (size_t m = 0; m < count; ++m) {
    if (s.stiffness[m].rows != vertex_count_ || s.stiffness[m].cols != vertex_count_)
      fail("the stiffness of '" + s.morphogens[m] + "' is not " + std::to_string(n) + " x " + std::to_string(n));
    if (s.initial[m].size() != n) fail("the initial layer of '" + s.morphogens[m] + "' has the wrong size");
    for (const double x : s.initial[m])
      if (!std::isfinite(x)) fail("the initial layer of '" + s.morphogens[m] + "' is not finite");
  }
  for (size_t c = 0; c < s.coefficients.size(); ++c)
    if (s.coefficients[c].size() != n) fail("coefficient '" + s.coefficient_names[c] + "' has the wrong size");
  for (const double m : s.mass)
    if (!(m > 0.0)) fail("every lumped mass must be > 0");
  if (!s.fixed.empty() && s.fixed.size() != n) fail("'fixed' must be empty or one entry per vertex");
  if (!(s.time_step > 0.0) || !std::isfinite(s.time_step)) fail("time_step must be > 0 and finite");
  if (s.substeps < 1) fail("substeps must be >= 1");
  if (!s.minimum.empty() && s.minimum.size() != count) fail("'minimum' must be empty or one floor per morphogen");
  for (const double floor : s.minimum)
    if (std::isnan(floor) || floor == std::numeric_limits<double>::infinity()) fail("every floor must be finite or -infinity");

  std::vector<std::string> names = s.morphogens;
  names.insert(names.end(), s.coefficient_names.begin(), s.coefficient_names.end());
  point_.assign(names.size(), 0.0);
  std::vector<double*> addresses;
  for (double& x : point_) addresses.push_back(&x);
  for (size_t m = 0; m < count; ++m) {
    formulas_.emplace_back(s.reaction[m], names, std::string(kWho) + ": reaction." + s.morphogens[m]);
    formulas_.back().bind(addresses);
  }
  layers_ = s.initial;
  reaction_.assign(count, std::vector<double>(n, 0.0));
  diffused_.assign(n, 0.0);
  if (s.integrator == ReactionIntegrator::Imex) factor_implicit_systems();
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
    if (factor->info() != Eigen::Success) fail("the implicit diffusion system of '" + s.morphogens[m] + "' could not be factored");
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
  if (system_.integrator == ReactionIntegrator::Imex) {
    imex_step(system_.time_step);
  } else {
    const double h = system_.time_step / system_.substeps;
    for (int s = 0; s < system_.substeps; ++s) explicit_substep(h);
  }
  ++steps_taken_;
  time_ = static_cast<double>(steps_taken_) * system_.time_step;
}

const IntrinsicVertexData<double>& ReferenceReactionDiffusion::checked_layer(int layer, const char* what) const {
  check_layer_index(layer, layer_count(), kWho, what);
  return layers_[static_cast<size_t>(layer)];
}

int ReferenceReactionDiffusion::add_static_layer(const IntrinsicVertexData<double>& values) {
  const int layer = layer_count();
  check_layer_values(values, vertex_count_, layer, kWho, "add_static_layer");
  layers_.push_back(values);
  return layer;
}

IntrinsicVertexData<double> ReferenceReactionDiffusion::field_values(int layer) const {
  return checked_layer(layer, "field_values");
}

void ReferenceReactionDiffusion::set_field(const IntrinsicVertexData<double>& values, int layer) {
  checked_layer(layer, "set_field");
  check_layer_values(values, vertex_count_, layer, kWho, "set_field");
  layers_[static_cast<size_t>(layer)] = values;
}

void ReferenceReactionDiffusion::fill_field(double value, int layer) {
  checked_layer(layer, "fill_field");
  check_layer_value(value, layer, kWho, "fill_field");
  IntrinsicVertexData<double>& f = layers_[static_cast<size_t>(layer)];
  f.assign(f.size(), value);
}

FieldStatistics ReferenceReactionDiffusion::field_statistics(double U, int layer) const {
  return compute_field_statistics(checked_layer(layer, "field_statistics"), system_.mass, U);
}

SimulationState ReferenceReactionDiffusion::save_state() const {
  SimulationState state;
  state.steps_taken = steps_taken_;
  state.time = time_;
  state.layers = layers_;
  return state;
}

void ReferenceReactionDiffusion::restore_state(const SimulationState& state) {
  check_state_fits(state, layer_count(), vertex_count_, 0, 0, "reaction-diffusion");
  for (size_t layer = 0; layer < layers_.size(); ++layer)
    std::copy(state.layers[layer].begin(), state.layers[layer].end(), layers_[layer].begin());
  steps_taken_ = state.steps_taken;
  time_ = state.time;
}

}  // namespace physarum
