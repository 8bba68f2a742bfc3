#include "opencl/diffusion_decay.hpp"

#include "common/base/errors.hpp"
#include "common/model/diffusion_decay.hpp"
#include "common/model/pheromone_operators.hpp"
#include "kernels/device_types.h"
#include "opencl/deposit_scale.hpp"
#include "opencl/runtime/flush_denormals.hpp"
#include "opencl/hybrid_matrix.hpp"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/kernel_sources.hpp"
#include "opencl/runtime/mapped_buffer.hpp"
#include "opencl/runtime/opencl_error.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "opencl/runtime/work_group_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum::opencl {

struct OpenCLDiffusionDecay::Kernels {
  cl::Kernel forward_substep, forward_overflow, add_deposits, csr_multiply, add_source;
};

namespace {

template <class Values>
std::vector<float> to_float(const Values& v) {
  return std::vector<float>(v.begin(), v.end());
}

// The same input checks as ReferenceDiffusionDecay, and the per-vertex quantities they pass.
struct CheckedInputs {
  IntrinsicVertexData<double> diffuse_over_mass, inverse_mass;
};

CheckedInputs checked_inputs(const SurfaceDomain& domain, const VertexParameters& params, double time_step,
                             const OpenCLDiffusionDecayOptions& options) {
  const int n = domain.vertex_count;
  const size_t un = static_cast<size_t>(n);
  if (!(time_step > 0.0) || !std::isfinite(time_step))
    throw InputError("opencl pheromone: time step " + std::to_string(time_step) + " must be > 0");
  if (n <= 0 || domain.vertex_mass.size() != un || domain.laplacian.rows != n || domain.laplacian.cols != n)
    throw InputError("opencl pheromone: the surface domain's mass (" + std::to_string(domain.vertex_mass.size()) +
                     ") or Laplacian (" + std::to_string(domain.laplacian.rows) + ") size differs from its " +
                     std::to_string(n) + " vertices");
  if (params[Param::diffuse_rate].size() != un || params[Param::decay_rate].size() != un)
    throw InputError("opencl pheromone: parameter maps have " + std::to_string(params[Param::decay_rate].size()) +
                     " values for " + std::to_string(n) + " vertices");
  if (options.cg_max_iterations < 1 || options.cg_check_interval < 1 || !(options.cg_relative_tolerance > 0.0))
    throw InputError("opencl pheromone: conjugate-gradient options need max iterations >= 1, check interval >= 1 "
                     "and tolerance > 0");
  CheckedInputs in{IntrinsicVertexData<double>(un), IntrinsicVertexData<double>(un)};
  for (int i = 0; i < n; ++i) {
    const double m = domain.vertex_mass[i];
    if (!(m > 0.0))
      throw InputError("opencl pheromone: vertex " + std::to_string(i) + " has lumped mass " + std::to_string(m) +
                       " (must be > 0)");
    if (!(params[Param::diffuse_rate][i] >= 0.0) || !(params[Param::decay_rate][i] >= 0.0))
      throw InputError("opencl pheromone: vertex " + std::to_string(i) + " has a negative diffuse or decay rate");
    in.inverse_mass[i] = 1.0 / m;
    in.diffuse_over_mass[i] = params[Param::diffuse_rate][i] / m;
  }
  return in;
}

}  // namespace

OpenCLDiffusionDecay::~OpenCLDiffusionDecay() = default;

void OpenCLDiffusionDecay::build_kernels() {
  kernels_ = std::make_unique<Kernels>();
  try {
    const std::string deposit_cells = fixed_point_deposits(compute_.device) ? "" : " -DPHYSARUM_FLOAT_DEPOSITS";
    const cl::Program program = build_program(compute_.context, compute_.device, "diffusion_decay.cl",
                                              kernel_source("diffusion_decay.cl"), options_.build_options + deposit_cells);
    Kernels& k = *kernels_;
    k.forward_substep = cl::Kernel(program, "pheromone_forward_substep");
    k.forward_overflow = cl::Kernel(program, "pheromone_forward_overflow");
    k.add_deposits = cl::Kernel(program, "pheromone_add_deposits");
    k.csr_multiply = cl::Kernel(program, "csr_multiply");
    k.add_source = cl::Kernel(program, "pheromone_add_source");
    // One local size for every per-vertex kernel; the smallest the kernels allow.
    group_ = common_work_group_size({&k.forward_substep, &k.forward_overflow, &k.add_deposits, &k.csr_multiply,
                                     &k.add_source},
                                    compute_.device, 256, sizeof(cl_float4));
  } catch (const cl::Error& e) {
    throw device_error("preparing the pheromone kernels (diffusion_decay.cl) on " + compute_.device.device_name, e.err());
  }
}

void OpenCLDiffusionDecay::upload_forward_matrix(const CsrMatrix& laplacian,
                                                 const IntrinsicVertexData<double>& diffuse_over_mass,
                                                 const IntrinsicVertexData<double>& decay_rate) {
  constexpr cl_mem_flags kRead = CL_MEM_READ_ONLY;
  // The sub-step matrix (common/model/pheromone_operators.hpp), in double, then in hybrid form with one
  // ELL row per work-item of the padded launch.
  const CsrMatrix F = forward_substep_matrix(laplacian, diffuse_over_mass, decay_rate, sub_step_);
  const HybridMatrix hybrid = to_hybrid(F, static_cast<int>(padded_global_size(static_cast<size_t>(vertex_count_), group_)));
  forward_stride_ = hybrid.stride;
  forward_overflow_rows_ = hybrid.overflow_rows();
  // The ELL block and the overflow part once each, u in once, u out written once and the long
  // rows' entries of it read and written again.
  forward_bytes_per_sub_step_ =
      4.0 * static_cast<double>(hybrid.column.size() + hybrid.value.size() + hybrid.overflow_row.size() +
                                hybrid.overflow_start.size() + hybrid.overflow_column.size() +
                                hybrid.overflow_value.size() + 2 * hybrid.overflow_row.size() + 2 * static_cast<size_t>(vertex_count_));
  forward_column_ = upload_buffer(compute_, "forward Euler ELL columns", hybrid.column, kRead, false);
  forward_value_ = upload_buffer(compute_, "forward Euler ELL values", hybrid.value, kRead, false);
  forward_overflow_row_ = upload_buffer(compute_, "forward Euler overflow rows", hybrid.overflow_row, kRead, false);
  forward_overflow_start_ =
      upload_buffer(compute_, "forward Euler overflow row starts", hybrid.overflow_start, kRead, false);
  forward_overflow_column_ =
      upload_buffer(compute_, "forward Euler overflow columns", hybrid.overflow_column, kRead, false);
  forward_overflow_value_ =
      upload_buffer(compute_, "forward Euler overflow values", hybrid.overflow_value, kRead, false);
  // Read only by the planted fault no-decay-substep (see pheromone_forward_substep).
  decay_rate_ = upload_buffer(compute_, "decay rate", to_float(decay_rate), kRead, false);
}

void OpenCLDiffusionDecay::prepare_backward_euler(const SurfaceDomain& domain, const VertexParameters& params,
                                                  double time_step) {
  constexpr cl_mem_flags kRead = CL_MEM_READ_ONLY;
  const int n = vertex_count_;
  const size_t un = static_cast<size_t>(n);
  const CsrMatrix& L = domain.laplacian;
  const OpenCLDiffusionDecayOptions& options = options_;
  // Eq. 7 as S u' = B u, S symmetric positive definite (common/model/pheromone_operators.hpp): B u on
  // this program's csr_multiply, S by conjugate gradients.
  const BackwardEulerSystem system =
      backward_euler_system(L, domain.vertex_mass, params[Param::diffuse_rate], params[Param::decay_rate], time_step);
  diagonal_only_ = system.diagonal_only;
  const bool on_host = !diagonal_only_ && (options.implicit_solver == ImplicitSolver::HostCholesky ||
                                           (options.implicit_solver == ImplicitSolver::Automatic &&
                                            implicit_solve_on_host(compute_.device, n)));
  if (on_host) {
    // B u on the host too, beside the solve: the step then costs no launch at all.
    host_solver_ = std::make_unique<HostCholeskySolve>(system.system, FactorPrecision::Single,
                                                       "opencl pheromone (backward Euler)");
    host_rhs_operator_ = system.rhs;
    host_rhs_.resize(un);
    if (options.host_solve_in_queue && runs_queued_host_tasks(compute_.device))
      host_task_ = std::make_unique<QueuedHostTask>(
          compute_, "opencl pheromone (backward Euler)",
          [this](void* u) { host_backward_solve(static_cast<float*>(u)); });
  } else {
    rhs_row_start_ = upload_buffer(compute_, "backward Euler rhs row starts", system.rhs.row_start, kRead, false);
    rhs_column_ = upload_buffer(compute_, "backward Euler rhs columns", system.rhs.column, kRead, false);
    rhs_value_ = upload_buffer(compute_, "backward Euler rhs values", to_float(system.rhs.value), kRead, false);
  }
  if (!diagonal_only_ && !on_host) {
    solver_ = std::make_unique<DeviceConjugateGradients>(
        compute_, system.system, system.inverse_diagonal,
        ConjugateGradientOptions{options.cg_relative_tolerance, options.cg_max_iterations, options.cg_check_interval},
        options.build_options);
  }
}

OpenCLDiffusionDecay::OpenCLDiffusionDecay(const ComputeContext& compute, const SurfaceDomain& domain,
                                 const VertexParameters& params, Integrator integrator, double time_step,
                                 const OpenCLDiffusionDecayOptions& options)
    : compute_(compute), options_(options), integrator_(integrator), time_step_(time_step) {
  const int n = domain.vertex_count;
  const size_t un = static_cast<size_t>(n);
  vertex_count_ = n;
  const CheckedInputs in = checked_inputs(domain, params, time_step, options);
  const CsrMatrix& L = domain.laplacian;

  // ---- forward Euler step limit: the reference's bound (common/model/diffusion_decay.hpp), in double,
  // so both backends take the same number of sub-steps ----
  stable_time_step_ = forward_euler_stable_step(L, in.diffuse_over_mass, params[Param::decay_rate]);
  if (integrator == Integrator::Forward) {
    sub_steps_ = forward_euler_sub_steps(time_step, stable_time_step_);
    sub_step_ = time_step / sub_steps_;
  }

  build_kernels();
  group_count_ = padded_global_size(un, group_) / group_;

  if (integrator == Integrator::Forward) upload_forward_matrix(L, in.diffuse_over_mass, params[Param::decay_rate]);
  mass_ = upload_buffer(compute, "vertex mass", to_float(domain.vertex_mass), CL_MEM_READ_ONLY, false);
  inverse_mass_ = upload_buffer(compute, "inverse vertex mass", to_float(in.inverse_mass), CL_MEM_READ_ONLY, false);
  u_ = allocate_written<cl_float>(compute, "concentration", un);
  scratch_ = allocate_written<cl_float>(compute, "concentration scratch", un);
  fill(0.0);

  if (integrator == Integrator::Backward) prepare_backward_euler(domain, params, time_step);
  statistics_ = std::make_unique<DeviceFieldStatistics>(compute, mass_.buffer, n);
}

// ---- the field ----

DeviceVertexData<double> OpenCLDiffusionDecay::concentration() const {
  return read_field_values(compute_, u_, vertex_count_, "pheromone field");
}

void OpenCLDiffusionDecay::set_concentration(const DeviceVertexData<double>& u) {
  write_field_values(compute_, u_, u, vertex_count_, "pheromone field");
}

void OpenCLDiffusionDecay::fill(double value) {
  compute_.queue.enqueueFillBuffer(u_.buffer, static_cast<float>(value), 0, u_.payload_bytes);
}

void OpenCLDiffusionDecay::add_deposits(const DeviceVertexData<double>& amount_per_vertex) {
  if (amount_per_vertex.size() != static_cast<size_t>(vertex_count_))
    throw InputError("opencl pheromone: add_deposits got " + std::to_string(amount_per_vertex.size()) +
                     " values for " + std::to_string(vertex_count_) + " vertices");
  // The amounts as accumulator cells: fixed point with the largest amount at most 2^62 units, or floats.
  const size_t n = amount_per_vertex.size();
  double largest = 0.0;
  for (double a : amount_per_vertex) largest = std::max(largest, std::abs(a));
  const bool fixed_point = fixed_point_deposits(compute_.device);
  const double scale = fixed_point ? fixed_point_scale_for(largest) : 1.0;
  std::vector<cl_long> units(fixed_point ? n : 0);
  std::vector<cl_float> floats(fixed_point ? 0 : n);
  for (size_t i = 0; i < n; ++i) {
    if (fixed_point) units[i] = std::llround(amount_per_vertex[i] * scale);
    else floats[i] = static_cast<cl_float>(amount_per_vertex[i]);
  }
  amount_ = fixed_point ? upload_buffer(compute_, "deposit amounts", units, CL_MEM_READ_WRITE, true)
                        : upload_buffer(compute_, "deposit amounts", floats, CL_MEM_READ_WRITE, true);
  add_deposits(amount_, scale);
  compute_.queue.finish();
}

void OpenCLDiffusionDecay::add_deposits(const DeviceBuffer& cells, double scale) {
  set_arguments(kernels_->add_deposits, static_cast<cl_int>(vertex_count_), cells, inverse_mass_,
                static_cast<cl_float>(1.0 / scale), u_);
  compute_.queue.enqueueNDRangeKernel(kernels_->add_deposits, cl::NullRange, cl::NDRange(group_count_ * group_),
                                      cl::NDRange(group_));
}

void OpenCLDiffusionDecay::advance(const DeviceBuffer& cells, double scale) {
  if (deposit_order(integrator_) == DepositOrder::AfterTransport) {
    step();
    add_deposits(cells, scale);
  } else {
    add_deposits(cells, scale);
    step();
  }
}

const cl::Buffer& OpenCLDiffusionDecay::concentration_buffer() const { return u_.buffer; }

// ---- time ----

void OpenCLDiffusionDecay::set_write_rate(const DeviceVertexData<double>& rate) {
  if (rate.empty()) {
    has_write_rate_ = false;
    write_rate_ = DeviceBuffer{};
    return;
  }
  if (rate.size() != static_cast<size_t>(vertex_count_))
    throw InputError("opencl pheromone: the write rate has " + std::to_string(rate.size()) + " values for " +
                     std::to_string(vertex_count_) + " vertices");
  for (size_t i = 0; i < rate.size(); ++i)
    if (!std::isfinite(rate[i]))
      throw InputError("opencl pheromone: the write rate at device vertex " + std::to_string(i) + " is " +
                       std::to_string(rate[i]) + " (must be finite)");
  write_rate_ = upload_buffer(compute_, "write rate", to_float(rate), CL_MEM_READ_ONLY, false);
  has_write_rate_ = true;
}

void OpenCLDiffusionDecay::add_source(double h, bool clamp_at_zero) {
  cl::Kernel& k = kernels_->add_source;
  set_arguments(k, static_cast<cl_int>(vertex_count_), static_cast<cl_float>(h), write_rate_,
                static_cast<cl_int>(clamp_at_zero ? 1 : 0), u_);
  compute_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(group_count_ * group_), cl::NDRange(group_));
}

void OpenCLDiffusionDecay::step() {
  try {
    if (integrator_ == Integrator::Forward) {
      forward_step();
      return;
    }
    // Backward Euler: the source joins the right-hand side, M (u + dt w), and the result is clamped.
    if (has_write_rate_) add_source(time_step_, false);
    if (diagonal_only_) diagonal_step();
    else backward_step();
    if (has_write_rate_) add_source(0.0, true);
  } catch (const cl::Error& e) {
    throw device_error("pheromone step on " + compute_.device.device_name, e.err());
  }
}

void OpenCLDiffusionDecay::forward_step() {
  cl::Kernel& k = kernels_->forward_substep;
  cl::Kernel& overflow = kernels_->forward_overflow;
  const cl::NDRange overflow_global(padded_global_size(static_cast<size_t>(forward_overflow_rows_), group_));
  // Ping-pong between u and scratch; an odd count ends in scratch and costs one device-side copy,
  // so u stays the buffer every other kernel knows. The queue is in order (compute_context.cpp), so
  // each overflow pass runs after its ELL pass.
  const cl::Buffer* from = &u_.buffer;
  const cl::Buffer* to = &scratch_.buffer;
  for (int s = 0; s < sub_steps_; ++s) {
    set_arguments(k, static_cast<cl_uint>(vertex_count_), static_cast<cl_uint>(forward_stride_), forward_column_,
                  forward_value_, decay_rate_, static_cast<cl_float>(sub_step_), *from, *to, static_cast<cl_uint>(s));
    compute_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(static_cast<size_t>(forward_stride_)),
                                        cl::NDRange(group_));
    if (forward_overflow_rows_ > 0) {
      set_arguments(overflow, static_cast<cl_uint>(forward_overflow_rows_), forward_overflow_row_,
                    forward_overflow_start_, forward_overflow_column_, forward_overflow_value_, *from, *to);
      compute_.queue.enqueueNDRangeKernel(overflow, cl::NullRange, overflow_global, cl::NDRange(group_));
    }
    std::swap(from, to);
    // The source term after the whole sub-step (ELL and overflow): it needs the field in u, so with a
    // write rate every sub-step ends there (one device-side copy each; only with write-stimuli).
    if (has_write_rate_) {
      if (from != &u_.buffer) {
        compute_.queue.enqueueCopyBuffer(scratch_.buffer, u_.buffer, 0, 0, u_.payload_bytes);
        std::swap(from, to);
      }
      add_source(sub_step_, true);
    }
  }
  if (from != &u_.buffer) compute_.queue.enqueueCopyBuffer(scratch_.buffer, u_.buffer, 0, 0, u_.payload_bytes);
}

void OpenCLDiffusionDecay::diagonal_step() {
  cl::Kernel& k = kernels_->csr_multiply;
  set_arguments(k, static_cast<cl_uint>(vertex_count_), rhs_row_start_, rhs_column_, rhs_value_, u_, scratch_);
  compute_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(group_count_ * group_), cl::NDRange(group_));
  compute_.queue.enqueueCopyBuffer(scratch_.buffer, u_.buffer, 0, 0, u_.payload_bytes);
  last_solve_ = {};
}

void OpenCLDiffusionDecay::backward_step() {
  if (host_solver_) {
    host_backward_step();
    return;
  }
  // b = B u, then S x = b with x = u (the previous field: a good first guess, and the solution is
  // written in place).
  const DeviceBuffer& b = solver_->right_hand_side();
  set_arguments(kernels_->csr_multiply, static_cast<cl_uint>(vertex_count_), rhs_row_start_, rhs_column_,
                rhs_value_, u_, b);
  compute_.queue.enqueueNDRangeKernel(kernels_->csr_multiply, cl::NullRange, cl::NDRange(group_count_ * group_),
                                      cl::NDRange(group_));
  last_solve_ = solver_->solve(u_);
}

// The whole step on the host, on the field in place: no launch, where the device path pays a launch,
// a read of b and a write of x, each a round trip that costs more than a small solve. In the
// device's queue where it can (host_task_: the step returns at once), else on the field mapped (one
// wait for the queue, and the unmap).
void OpenCLDiffusionDecay::host_backward_step() {
  last_solve_ = {};
  if (host_task_) {
    host_task_->enqueue(u_);
    return;
  }
  const MappedBuffer<float> u(compute_, u_, CL_MAP_READ | CL_MAP_WRITE, 0, static_cast<size_t>(vertex_count_));
  host_backward_solve(u.data());
}

// b = B u (B is mostly diagonal), then x = S^-1 b written over u.
void OpenCLDiffusionDecay::host_backward_solve(float* u) {
  const FlushDenormalsToZero flush;  // the field's tails (opencl/runtime/flush_denormals.hpp)
  const CsrMatrix& B = host_rhs_operator_;
  for (int i = 0; i < vertex_count_; ++i) {
    double sum = 0.0;
    for (int k = B.row_start[i]; k < B.row_start[i + 1]; ++k) sum += B.value[k] * u[static_cast<size_t>(B.column[k])];
    host_rhs_[static_cast<size_t>(i)] = static_cast<float>(sum);
  }
  host_solver_->solve(host_rhs_.data(), u);
}

// ---- summaries ----

double OpenCLDiffusionDecay::total_amount() const { return statistics_->weighted_sum(u_.buffer); }

FieldStatistics OpenCLDiffusionDecay::statistics(double U) const { return statistics_->compute(u_.buffer, U); }

std::vector<std::string> OpenCLDiffusionDecay::damaged_canaries() const {
  std::vector<std::string> damaged = statistics_->damaged_canaries();
  for (const DeviceBuffer* b : {&u_, &scratch_, &amount_})
    if (!canary_intact(compute_, *b)) damaged.push_back(b->name);
  if (solver_)
    for (const std::string& name : solver_->damaged_canaries()) damaged.push_back(name);
  return damaged;
}

}  // namespace physarum::opencl
