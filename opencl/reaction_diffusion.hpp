#pragma once
// A reaction-diffusion system (common/reaction_diffusion/reaction_diffusion_system.hpp) advanced on an OpenCL device,
// as a SimulationBackend whose dynamic layers are the morphogens (layer m = morphogen m) and which
// has no agents. The morphogens stay on the device; the host reads them only on demand.
//
//   Explicit: each step is `substeps` forward-Euler sub-steps
//               u_m += h (-(K_m u_m)_i / mass_i + R_m(u)_i),   h = time_step / substeps,
//             one fused launch per sub-step for all morphogens (kernels/reaction_diffusion.cl:
//             neighbours through the shared sparsity pattern, kinetics inline), plus a small launch
//             for the rows longer than the ELL width. Double-buffered: the two halves take turns
//             as the current state, so a sub-step moves exactly what it must and no step ends in a
//             copy (an odd sub-step count used to copy the whole state back, ~15 % of a step).
//   IMEX:     (M + h K_m) u_m' = M (u_m + h R_m(u)) per morphogen: the right-hand side on the device,
//             the solve either by Jacobi-preconditioned conjugate gradients on the device
//             (opencl/conjugate_gradients.hpp, warm-started from the previous step's values) or by a
//             sparse Cholesky factorization on the host, made once (opencl/host_cholesky_solve.hpp,
//             the pheromone's; see ImexSolver).
//
// The formulas are compiled into the program (opencl/reaction_formula.hpp): a coefficient with one
// value everywhere becomes a float literal, a varying one a per-vertex buffer read. Held (`fixed`)
// vertices keep their values exactly, in both integrators.
//
// Vertices are in the domain's (= the system's) order; there is no device renumbering here.
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/surface_domain.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/conjugate_gradients.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/field_statistics.hpp"
#include "opencl/host_cholesky_solve.hpp"
#include "opencl/static_field.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace physarum::opencl {

// Who solves the IMEX step's linear systems.
enum class ImexSolver {
  // implicit_solve_on_host (opencl/host_cholesky_solve.hpp), as for the pheromone: the host's float
  // factorization where the device is the host's CPU (PoCL): there its two triangular solves per
  // morphogen, on the fields mapped in place, beat tens of CG iterations at every size
  // (bench_reaction_diffusion); on a GPU, where the values never leave the device and CG's
  // bandwidth-bound iterations run at its speed, only for systems too small to fill it.
  Automatic,
  DeviceConjugateGradients,
  HostFactorization,
};

struct OpenCLReactionDiffusionOptions {
  ImexSolver imex_solver = ImexSolver::Automatic;
  // Device CG stops when ||b - S x|| <= tolerance ||b|| (1e-6: about 10 float ulps).
  double cg_relative_tolerance = 1e-6;
  int cg_max_iterations = 1000;
  int cg_check_interval = 8;
  // Extra OpenCL build options (the differential harness plants faults with -D flags,
  // opencl/planted_faults.hpp: rd-swap-diffusion, rd-no-feed).
  std::string build_options;
};

class OpenCLReactionDiffusion final : public SimulationBackend {
 public:
  // Checks the system (2 to 4 morphogens with one formula each, every per-vertex array one value per
  // domain vertex and finite, masses > 0, stiffness matrices n x n sharing one sparsity pattern,
  // time step > 0, substeps >= 1, formulas that parse over the morphogen and coefficient names),
  // throwing InputError saying what and where; translates the formulas, builds the program and
  // uploads the operators and the initial state. DeviceError when the device refuses.
  OpenCLReactionDiffusion(const ComputeContext& compute, const SurfaceDomain& domain,
                          const ReactionDiffusionSystem& system, const OpenCLReactionDiffusionOptions& options = {});
  ~OpenCLReactionDiffusion() override;
  OpenCLReactionDiffusion(const OpenCLReactionDiffusion&) = delete;
  OpenCLReactionDiffusion& operator=(const OpenCLReactionDiffusion&) = delete;

  // One time step (see the header comment): explicit steps only enqueue; IMEX waits for its solves.
  void step() override;
  void run(long long steps) override;
  void finish() override;

  int layer_count() const override { return morphogen_count_ + static_cast<int>(static_fields_.size()); }
  int dynamic_layer_count() const override { return morphogen_count_; }
  int add_static_layer(const IntrinsicVertexData<double>& values) override;
  IntrinsicVertexData<double> field_values(int layer = 0) const override;
  // Setting a morphogen sets its held vertices too (they keep the new values from then on).
  void set_field(const IntrinsicVertexData<double>& values, int layer = 0) override;
  void fill_field(double value, int layer = 0) override;
  FieldStatistics field_statistics(double U, int layer = 0) const override;

  double time() const override { return static_cast<double>(steps_taken_) * time_step_; }
  long long steps_taken() const override { return steps_taken_; }
  // The layers and the step count (the time follows from it): no agents, and nothing else carries
  // over a step (the CG's first guess is the layer itself).
  SimulationState save_state() const override;
  void restore_state(const SimulationState& state) override;
  std::vector<int> agent_faces() const override { return {}; }
  SimulationCounters counters() const override { return {}; }
  std::string backend_name() const override { return "opencl"; }
  std::string device_name() const override;

  // ---- for tests and benchmarks ----
  // The OpenCL C expressions the formulas were compiled to, one per morphogen.
  const std::vector<std::string>& translated_reactions() const { return translated_; }
  // The IMEX solver in use (Automatic resolved); meaningless for the explicit integrator.
  ImexSolver imex_solver() const { return imex_solver_; }
  const ConjugateGradientReport& last_solve() const { return last_solve_; }
  // Bytes one explicit sub-step reads and writes at the least: the shared columns and every
  // morphogen's values of the hybrid matrix, u in and out, the varying coefficients and the held
  // flags (when any): the memory traffic a roofline sets against the bandwidth.
  double bytes_per_sub_step() const { return bytes_per_sub_step_; }
  int substeps() const { return substeps_; }
  std::vector<std::string> damaged_canaries() const;

 private:
  struct Kernels;
  // What the constructor's steps hand on to each other (defined in the .cpp; gone once built).
  struct Setup;
  // The constructor's steps, in the constructor's order (each needs the ones before it).
  // The formulas as OpenCL C (translated_), and which coefficients are read per vertex.
  void translate_kinetics(const ReactionDiffusionSystem& system, Setup& setup);
  // Whether every K_m is c_m K_0, so that the explicit sub-step reads one set of weights.
  void find_shared_weights(const ReactionDiffusionSystem& system, Setup& setup) const;
  // The explicit sub-step's W_m = -h M^-1 K_m and their ELL width (none for IMEX).
  void make_substep_matrices(const ReactionDiffusionSystem& system, Setup& setup) const;
  // The floors as literals; has_floors_.
  void write_floors(const ReactionDiffusionSystem& system, Setup& setup);
  // The #defines that compile the system into kernels/reaction_diffusion.cl.
  std::string kernel_prelude(const Setup& setup) const;
  // Builds the program, takes its kernels and their common work-group size (group_).
  void build_kernels(const std::string& prelude);
  // stride_: vertices padded to the work-group size and the device's sub-buffer alignment.
  void choose_stride();
  // The varying coefficients, the held flags and the masses.
  void upload_vertex_data(const ReactionDiffusionSystem& system, const std::vector<size_t>& varying);
  // The state's halves (two explicit, one IMEX), zeroed, with their per-morphogen views.
  void allocate_state(const ReactionDiffusionSystem& system);
  // Explicit: the W_m in hybrid form; bytes_per_sub_step_.
  void upload_explicit_operator(const Setup& setup);
  // IMEX: the solver choice, the right-hand side buffers and one solver per morphogen.
  void make_imex_solvers(const ReactionDiffusionSystem& system);
  void explicit_step();
  void imex_step();
  void host_imex_solve();
  void apply_floors(const cl::Buffer& u);
  void update_dirichlet_coupling();
  void check_morphogen(int layer, const char* what) const;

  ComputeContext compute_;
  OpenCLReactionDiffusionOptions options_;
  Integrator integrator_;
  int vertex_count_ = 0;
  int morphogen_count_ = 0;
  double time_step_ = 0.0;
  int substeps_ = 1;
  double sub_step_ = 0.0;
  long long steps_taken_ = 0;
  bool has_fixed_ = false;
  bool has_floors_ = false;  // some morphogen has a floor (ReactionDiffusionSystem::minimum)
  std::vector<std::string> translated_;

  std::unique_ptr<Kernels> kernels_;
  std::size_t group_ = 1;
  std::size_t stride_ = 1;  // padded per-vertex length of every array (a multiple of group_)
  // Explicit: hybrid matrices W_m = -h M^-1 K_m (columns shared, values per morphogen).
  int overflow_rows_ = 0;
  int overflow_entries_ = 0;
  double bytes_per_sub_step_ = 0.0;
  DeviceBuffer column_, value_, overflow_row_, overflow_start_, overflow_column_, overflow_value_;
  // Per vertex: varying coefficients (block per coefficient), held flags, masses.
  DeviceBuffer coefficients_, fixed_, mass_;
  std::vector<std::uint8_t> fixed_host_;
  std::vector<CsrMatrix> stiffness_;  // kept for the Dirichlet coupling (IMEX with held vertices)
  // State: u (block per morphogen) in state_[current_]; the explicit integrator writes each sub-step
  // into the other half and makes it current (IMEX has one half and works in place). Everything that
  // reads or writes the morphogens goes through state() and state_view(), never a half by number.
  std::array<DeviceBuffer, 2> state_;
  int current_ = 0;
  std::array<std::vector<DeviceBuffer>, 2> state_views_;  // per half, sub-buffers, one per morphogen
  const DeviceBuffer& state() const { return state_[static_cast<size_t>(current_)]; }
  const DeviceBuffer& state_view(int morphogen) const {
    return state_views_[static_cast<size_t>(current_)][static_cast<size_t>(morphogen)];
  }
  // Five or more morphogens with the explicit integrator are stored vertex by vertex
  // (RD_INTERLEAVED in reaction_diffusion.cl): no sub-buffers then; a morphogen is copied out into
  // `lane_` (one block) to be read or summarised, and written by reading, changing and writing the
  // whole state on the host.
  bool interleaved_ = false;
  DeviceBuffer lane_;
  const DeviceBuffer& morphogen_block(int morphogen) const;  // state_view, or the morphogen copied into lane_
  std::vector<float> read_state() const;                      // the whole state of an interleaved run
  void write_morphogen(int morphogen, const std::vector<float>& values);
  DeviceBuffer rhs_, coupling_;  // IMEX: b, and the held vertices' contribution to it
  // IMEX.
  ImexSolver imex_solver_ = ImexSolver::Automatic;
  std::vector<std::unique_ptr<DeviceConjugateGradients>> solvers_;
  std::vector<std::unique_ptr<HostCholeskySolve>> host_solvers_;  // one per morphogen
  std::vector<float> held_solution_;  // with held vertices: a solve's result before the free ones are kept
  ConjugateGradientReport last_solve_;

  IntrinsicVertexData<double> mass_host_;
  std::unique_ptr<DeviceFieldStatistics> statistics_;
  std::vector<std::unique_ptr<OpenCLStaticField>> static_fields_;
};

}  // namespace physarum::opencl
