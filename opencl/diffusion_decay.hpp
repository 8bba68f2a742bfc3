#pragma once
// The diffusion-decay field model on the OpenCL device (common/model/diffusion_decay.hpp defines it;
// reference/diffusion_decay.hpp is the serial counterpart): one layer of one float per intrinsic
// vertex, advanced by Eq. 1 with the cotan Laplacian L and lumped mass M (Eq. 6 forward Euler with
// automatic sub-steps, Eq. 7 backward Euler by conjugate gradients on the device). The field stays on
// the device; the host reads it only on demand. An optional write rate (Sec. 3.3 write-stimuli) is a
// source term, added and clamped at zero exactly where the reference does (pheromone_add_source).
#include "common/base/element_data.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/model/diffusion_decay.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/model/vertex_parameters.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/conjugate_gradients.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/field_model.hpp"
#include "opencl/field_statistics.hpp"
#include "opencl/host_cholesky_solve.hpp"
#include "opencl/runtime/queued_host_task.hpp"

#include <memory>
#include <string>
#include <vector>

namespace physarum::opencl {

// How the backward-Euler system is solved: conjugate gradients on the device, or a Cholesky factor on
// the host (opencl/host_cholesky_solve.hpp). Automatic asks implicit_solve_on_host: the host factor
// on a CPU device (its memory is the host's; measured faster there at every size, see the README),
// and on a GPU only for systems small enough that CG's fixed cost of launches dominates.
enum class ImplicitSolver { Automatic, DeviceConjugateGradients, HostCholesky };

struct OpenCLDiffusionDecayOptions {
  ImplicitSolver implicit_solver = ImplicitSolver::Automatic;
  // With the host factor: solve inside the device's queue, as a native kernel on the field in place
  // (opencl/runtime/queued_host_task.hpp), where the device runs them (PoCL's CPU device), so a step never
  // waits for the device; elsewhere, or when false, the host maps the field and solves (one wait per
  // step). The same arithmetic either way: the fields agree bit for bit.
  bool host_solve_in_queue = true;
  // Backward Euler stops when ||b - S x|| <= tolerance ||b|| (S, b: the symmetrised system,
  // common/model/pheromone_operators.hpp). 1e-6 is about 10 float ulps: tighter is not reachable in float32.
  double cg_relative_tolerance = 1e-6;
  int cg_max_iterations = 1000;  // a bound, so a solve always ends
  // Iterations enqueued between two reads of the solver state (a 32-byte read): fewer reads, but up
  // to this many no-op launches after convergence.
  int cg_check_interval = 16;
  // Extra OpenCL build options (the differential harness plants faults with -D flags).
  std::string build_options;
};

class OpenCLDiffusionDecay final : public OpenCLFieldLayer {
 public:
  // Uploads the operators the integrator needs (forward Euler: the sub-step matrix, see diffusion_decay.cl;
  // backward Euler: the symmetrised system), masses and the per-vertex rates of params, all in
  // float with int indices; builds diffusion_decay.cl. Throws InputError like ReferenceDiffusionDecay (sizes, time step,
  // masses, rates) and DeviceError when a buffer exceeds the device's limits or a build fails.
  OpenCLDiffusionDecay(const ComputeContext& compute, const SurfaceDomain& domain, const VertexParameters& params,
                  Integrator integrator, double time_step, const OpenCLDiffusionDecayOptions& options = {});
  ~OpenCLDiffusionDecay();
  OpenCLDiffusionDecay(const OpenCLDiffusionDecay&) = delete;
  OpenCLDiffusionDecay& operator=(const OpenCLDiffusionDecay&) = delete;

  // ---- the field ----
  // The field in the device's vertex order (the domain this was built from is renumbered so).
  DeviceVertexData<double> concentration() const override;  // blocking read-back, converted to double
  void set_concentration(const DeviceVertexData<double>& u) override;
  void fill(double value) override;
  // An AMOUNT at a vertex raises its concentration by amount / vertex_mass (blocking; for tests).
  void add_deposits(const DeviceVertexData<double>& amount_per_vertex);
  // The same from the device's deposit accumulator (kernels/deposit_cells.h: fixed point of `scale`
  // where fixed_point_deposits(device), floats elsewhere), which is cleared: enqueues one launch.
  void add_deposits(const DeviceBuffer& cells, double scale);
  // The device buffer holding u (float, vertex_count): the same buffer for the object's lifetime,
  // so agent kernels may keep it as an argument.
  const cl::Buffer& concentration_buffer() const override;

  // ---- time ----
  // One time step: forward Euler enqueues its sub-steps back to back with no host round trip;
  // backward Euler runs conjugate gradients, reading only the 32-byte solver state every
  // cg_check_interval iterations. Throws DeviceError when a solve ends far from convergence.
  void step();
  // The write rate per vertex in the device's vertex order (concentration/s, finite; InputError
  // naming the vertex otherwise), or empty for none (the base model, no extra launch).
  void set_write_rate(const DeviceVertexData<double>& rate);
  // One time step with the step's deposits, in the order the integrator needs (deposit_order).
  void advance(const DeviceBuffer& cells, double scale) override;
  double time_step() const { return time_step_; }
  Integrator integrator() const { return integrator_; }
  double stable_time_step() const { return stable_time_step_; }  // same bound as the reference
  int sub_steps() const { return sub_steps_; }
  // Bytes one forward-Euler sub-step reads and writes at the least (its matrix once, u in and out):
  // the memory traffic a roofline sets against the bandwidth. 0 for backward Euler.
  double forward_bytes_per_sub_step() const { return forward_bytes_per_sub_step_; }
  // The last backward-Euler CG solve (iterations 0 when the host factor solves the system).
  const ConjugateGradientReport& last_solve() const { return last_solve_; }
  bool solves_on_host() const { return host_solver_ != nullptr; }
  // The host factor solves in the device's queue (OpenCLDiffusionDecayOptions::host_solve_in_queue).
  bool solves_in_queue() const { return host_task_ != nullptr; }

  // ---- summaries, reduced on the device ----
  double total_amount() const override;  // sum_i m_i u_i
  FieldStatistics statistics(double U) const override;
  int vertex_count() const { return vertex_count_; }

  // Names of the device buffers whose canary region a kernel overwrote (empty when none): the
  // out-of-bounds check of the tests.
  std::vector<std::string> damaged_canaries() const override;

 private:
  struct Kernels;
  // The constructor's parts: the programs and launch size; the forward sub-step matrix on the
  // device; the backward-Euler system, solved on the host or by device conjugate gradients.
  void build_kernels();
  void upload_forward_matrix(const CsrMatrix& laplacian, const IntrinsicVertexData<double>& diffuse_over_mass,
                             const IntrinsicVertexData<double>& decay_rate);
  void prepare_backward_euler(const SurfaceDomain& domain, const VertexParameters& params, double time_step);
  void forward_step();
  void backward_step();
  void host_backward_step();
  void host_backward_solve(float* u);
  void diagonal_step();
  void add_source(double h, bool clamp_at_zero);

  ComputeContext compute_;
  OpenCLDiffusionDecayOptions options_;
  Integrator integrator_;
  double time_step_;
  int vertex_count_ = 0;
  double stable_time_step_ = 0.0;
  int sub_steps_ = 1;
  double sub_step_ = 0.0;
  // Backward Euler with R_dif = 0 everywhere: the system is diagonal and one multiply solves it.
  bool diagonal_only_ = false;

  std::unique_ptr<Kernels> kernels_;
  std::size_t group_ = 1;        // local size of every per-vertex kernel
  std::size_t group_count_ = 1;  // work-groups of a per-vertex launch

  // Operators and per-vertex data (read-only on the device).
  DeviceBuffer mass_, inverse_mass_;
  // Forward Euler: the sub-step matrix in hybrid ELL + CSR form (opencl/hybrid_matrix.hpp), and the
  // decay rates for the planted fault no-decay-substep.
  int forward_stride_ = 0;
  int forward_overflow_rows_ = 0;
  double forward_bytes_per_sub_step_ = 0.0;
  DeviceBuffer forward_column_, forward_value_, decay_rate_;
  DeviceBuffer forward_overflow_row_, forward_overflow_start_, forward_overflow_column_, forward_overflow_value_;
  // Backward Euler: S x = B u (common/model/pheromone_operators.hpp); B here, S in the solver (absent when
  // the system is diagonal).
  DeviceBuffer rhs_row_start_, rhs_column_, rhs_value_;
  std::unique_ptr<DeviceConjugateGradients> solver_;   // one of these two
  std::unique_ptr<HostCholeskySolve> host_solver_;
  CsrMatrix host_rhs_operator_;  // B, with the host solver
  std::vector<float> host_rhs_;  // B u, with the host solver
  // Written by kernels: canary-guarded.
  DeviceBuffer u_, scratch_, amount_;
  // The write rate (empty buffer and has_write_rate_ false when none).
  DeviceBuffer write_rate_;
  bool has_write_rate_ = false;

  std::unique_ptr<DeviceFieldStatistics> statistics_;
  ConjugateGradientReport last_solve_;
  // The host solve as a native kernel (host_solve_in_queue). Declared last, so it is destroyed first:
  // its destructor waits for runs still queued, which use the host solver and buffers above.
  std::unique_ptr<QueuedHostTask> host_task_;
};

}  // namespace physarum::opencl
