#pragma once
// The serial reference backend of a reaction–diffusion system (common/reaction_diffusion/reaction_diffusion_system.hpp):
// the oracle the OpenCL backend is judged against. Its dynamic layers are the morphogens, in the
// system's order; it has no agents (agent_faces() is empty, the counters stay zero).
//
// One step() advances time by system.time_step:
//   Explicit  `substeps` forward-Euler sub-steps of h = time_step / substeps, each
//               u_m <- u_m + h (R_m(u) - M^-1 K_m u_m)
//             with the reaction evaluated on the state at the start of the sub-step;
//   Imex      u_m' solves (M + dt K_m) u_m' = M (u_m + dt R_m(u)): the diffusion implicit (one
//             sparse LDL^T factorization per morphogen, made once), the reaction explicit.
// Vertices with `fixed` set keep their values (a Dirichlet region: in IMEX they are moved to the
// right-hand side, and the factored system is the one of the free vertices).
// The reaction formulas are evaluated per vertex with muparser (common/reaction_diffusion/reaction_formula.hpp).
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "reference/field_layers.hpp"
#include "common/reaction_diffusion/reaction_formula.hpp"
#include "common/simulation/simulation_backend.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace physarum {

class ReferenceReactionDiffusion final : public SimulationBackend {
 public:
  // InputError (starting "reaction-diffusion:") when the arrays do not match one another (one
  // stiffness, initial layer and formula per morphogen, one value per vertex everywhere), the time
  // step is not > 0, substeps < 1, a formula does not parse or a factorization fails.
  explicit ReferenceReactionDiffusion(ReactionDiffusionSystem system);
  ReferenceReactionDiffusion(const ReferenceReactionDiffusion&) = delete;
  ReferenceReactionDiffusion& operator=(const ReferenceReactionDiffusion&) = delete;

  void step() override;

  const ReactionDiffusionSystem& system() const { return system_; }
  int morphogen_count() const { return static_cast<int>(system_.morphogens.size()); }
  // The layer itself (any layer; std::out_of_range past the end).
  const IntrinsicVertexData<double>& field(int layer) const { return layers_.at(layer); }

  // ---- SimulationBackend ----
  int layer_count() const override { return layers_.size(); }
  int dynamic_layer_count() const override { return morphogen_count(); }
  int add_static_layer(const IntrinsicVertexData<double>& values) override { return layers_.add_static(values); }
  IntrinsicVertexData<double> field_values(int layer = 0) const override { return layers_.checked(layer, "field_values"); }
  void set_field(const IntrinsicVertexData<double>& values, int layer = 0) override { layers_.set(values, layer); }
  void fill_field(double value, int layer = 0) override { layers_.fill(value, layer); }
  FieldStatistics field_statistics(double U, int layer = 0) const override;
  double time() const override { return time_; }
  long long steps_taken() const override { return steps_taken_; }
  std::vector<int> agent_faces() const override { return {}; }
  SimulationCounters counters() const override { return {}; }
  // The layers, the step count and the time: no agents, and nothing else carries over a step.
  SimulationState save_state() const override;
  void restore_state(const SimulationState& state) override;
  std::string backend_name() const override { return "reference"; }
  std::string device_name() const override { return "CPU (serial reference, 1 thread)"; }

 private:
  // reaction_[m][i] = R_m at vertex i, from the current layers.
  void evaluate_reaction();
  void explicit_substep(double h);
  void imex_step(double dt);
  void factor_implicit_systems();
  // Raises the free vertices of morphogen m below its floor (ReactionDiffusionSystem::minimum) to it.
  void apply_floor(size_t m);
  bool is_fixed(size_t vertex) const { return !system_.fixed.empty() && system_.fixed[vertex] != 0; }

  ReactionDiffusionSystem system_;
  int vertex_count_ = 0;
  FieldLayers layers_;  // morphogens, then static layers
  double time_ = 0.0;
  long long steps_taken_ = 0;

  // The formulas, bound to point_: the morphogens' then the coefficients' values at one vertex.
  std::vector<ReactionFormula> formulas_;
  std::vector<double> point_;
  std::vector<std::vector<double>> reaction_;  // per morphogen, per vertex
  std::vector<double> diffused_;               // K_m u_m, scratch

  // IMEX: the free vertices (not fixed), their position in the reduced system (-1 for fixed ones),
  // one factorization of (M + dt K_m) restricted to them per morphogen, and the coupling to the
  // fixed vertices (the columns moved to the right-hand side).
  std::vector<int> free_vertices_;
  std::vector<int> reduced_index_;
  std::vector<std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>> factor_;
  std::vector<Eigen::SparseMatrix<double, Eigen::RowMajor>> coupling_;  // free rows x all columns, fixed columns only
};

}  // namespace physarum
