#include "opencl/pheromone.hpp"

#include "common/errors.hpp"
#include "common/forward_euler_limit.hpp"
#include "kernels/device_types.h"
#include "opencl/kernel_arguments.hpp"
#include "opencl/kernel_sources.hpp"
#include "opencl/opencl_error.hpp"
#include "opencl/program_cache.hpp"
#include "opencl/hybrid_matrix.hpp"
#include "opencl/work_group_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum::opencl {

struct OpenCLPheromone::Kernels {
  cl::Kernel forward_substep, forward_overflow, add_amounts, csr_multiply;
  cl::Kernel cg_start, cg_start_finish, cg_multiply, cg_alpha, cg_update, cg_beta, cg_direction;
};

namespace {

static_assert(sizeof(PhysarumCgState) == 32, "PhysarumCgState: eight 4-byte fields on host and device");

std::vector<float> to_float(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

// A CSR matrix assembled row by row on the host, in double, converted to float when uploaded.
struct HostCsr {
  std::vector<int> row_start{0};
  std::vector<int> column;
  std::vector<double> value;
  void add(int col, double v) {
    column.push_back(col);
    value.push_back(v);
  }
  void end_row() { row_start.push_back(static_cast<int>(column.size())); }
};

}  // namespace

OpenCLPheromone::~OpenCLPheromone() = default;

OpenCLPheromone::OpenCLPheromone(const ComputeContext& compute, const SurfaceDomain& domain,
                                 const VertexParameters& params, Integrator integrator, double time_step,
                                 const OpenCLPheromoneOptions& options)
    : compute_(compute), options_(options), integrator_(integrator), time_step_(time_step) {
  const int n = domain.vertex_count;
  const size_t un = static_cast<size_t>(n);
  vertex_count_ = n;
  // ---- the same input checks as ReferencePheromone ----
  if (!(time_step > 0.0) || !std::isfinite(time_step))
    throw InputError("opencl pheromone: time step " + std::to_string(time_step) + " must be > 0");
  if (n <= 0 || domain.vertex_mass.size() != un || domain.laplacian.rows != n || domain.laplacian.cols != n)
    throw InputError("opencl pheromone: the surface domain's mass (" + std::to_string(domain.vertex_mass.size()) +
                     ") or Laplacian (" + std::to_string(domain.laplacian.rows) + ") size differs from its " +
                     std::to_string(n) + " vertices");
  if (params.diffuse_rate.size() != un || params.decay_rate.size() != un)
    throw InputError("opencl pheromone: parameter maps have " + std::to_string(params.decay_rate.size()) +
                     " values for " + std::to_string(n) + " vertices");
  if (options.cg_max_iterations < 1 || options.cg_check_interval < 1 || !(options.cg_relative_tolerance > 0.0))
    throw InputError("opencl pheromone: conjugate-gradient options need max iterations >= 1, check interval >= 1 "
                     "and tolerance > 0");
  const CsrMatrix& L = domain.laplacian;
  std::vector<double> diffuse_over_mass(un), inverse_mass(un);
  for (int i = 0; i < n; ++i) {
    const double m = domain.vertex_mass[i];
    if (!(m > 0.0))
      throw InputError("opencl pheromone: vertex " + std::to_string(i) + " has lumped mass " + std::to_string(m) +
                       " (must be > 0)");
    if (!(params.diffuse_rate[i] >= 0.0) || !(params.decay_rate[i] >= 0.0))
      throw InputError("opencl pheromone: vertex " + std::to_string(i) + " has a negative diffuse or decay rate");
    inverse_mass[i] = 1.0 / m;
    diffuse_over_mass[i] = params.diffuse_rate[i] / m;
  }

  // ---- forward Euler step limit: the reference's bound (common/forward_euler_limit.hpp), in double,
  // so both backends take the same number of sub-steps ----
  stable_time_step_ = forward_euler_stable_step(L, diffuse_over_mass, params.decay_rate);
  if (integrator == Integrator::ForwardEuler) {
    sub_steps_ = forward_euler_sub_steps(time_step, stable_time_step_);
    sub_step_ = time_step / sub_steps_;
  }

  // ---- program and launch sizes ----
  kernels_ = std::make_unique<Kernels>();
  try {
    const cl::Program program =
        build_program(compute.context, compute.device, "pheromone.cl", kernel_source("pheromone.cl"),
                      options.build_options);
    Kernels& k = *kernels_;
    k.forward_substep = cl::Kernel(program, "pheromone_forward_substep");
    k.forward_overflow = cl::Kernel(program, "pheromone_forward_overflow");
    k.add_amounts = cl::Kernel(program, "pheromone_add_amounts");
    k.csr_multiply = cl::Kernel(program, "csr_multiply");
    k.cg_start = cl::Kernel(program, "cg_start");
    k.cg_start_finish = cl::Kernel(program, "cg_start_finish");
    k.cg_multiply = cl::Kernel(program, "cg_multiply");
    k.cg_alpha = cl::Kernel(program, "cg_alpha");
    k.cg_update = cl::Kernel(program, "cg_update");
    k.cg_beta = cl::Kernel(program, "cg_beta");
    k.cg_direction = cl::Kernel(program, "cg_direction");
    // One local size for every per-vertex kernel, so all reductions have the same number of
    // partials; the smallest the kernels allow.
    group_ = 256;
    for (const cl::Kernel* kernel : {&k.forward_substep, &k.forward_overflow, &k.add_amounts, &k.csr_multiply,
                                     &k.cg_start, &k.cg_multiply, &k.cg_update, &k.cg_direction})
      group_ = std::min(group_, work_group_size(*kernel, compute.device, 256, sizeof(cl_float4)));
    final_group_ = 256;
    for (const cl::Kernel* kernel : {&k.cg_start_finish, &k.cg_alpha, &k.cg_beta})
      final_group_ = std::min(final_group_, work_group_size(*kernel, compute.device, 256, sizeof(cl_float4)));
  } catch (const cl::Error& e) {
    throw device_error("preparing the pheromone kernels (pheromone.cl) on " + compute.device.device_name, e.err());
  }
  group_count_ = padded_global_size(un, group_) / group_;

  // ---- buffers ----
  constexpr cl_mem_flags kRead = CL_MEM_READ_ONLY;
  const size_t field_bytes = un * sizeof(float);
  if (integrator == Integrator::ForwardEuler) {
    // The sub-step matrix F = I - h (diag(r_dif / m) L + diag(r_dec)), in double, then in hybrid
    // form with one ELL row per work-item of the padded launch.
    CsrMatrix F;
    F.rows = F.cols = n;
    F.row_start.push_back(0);
    for (int i = 0; i < n; ++i) {
      const double keep = 1.0 - sub_step_ * params.decay_rate[i];
      bool diagonal = false;
      for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
        const int j = L.column[k];
        F.column.push_back(j);
        F.value.push_back(-sub_step_ * diffuse_over_mass[i] * L.value[k] + (j == i ? keep : 0.0));
        diagonal |= j == i;
      }
      if (!diagonal) F.column.push_back(i), F.value.push_back(keep);  // a Laplacian row without a diagonal entry
      F.row_start.push_back(static_cast<int>(F.column.size()));
    }
    const HybridMatrix hybrid = to_hybrid(F, static_cast<int>(padded_global_size(un, group_)));
    forward_stride_ = hybrid.stride;
    forward_overflow_rows_ = hybrid.overflow_rows();
    // The ELL block and the overflow part once each, u in once, u out written once and the long
    // rows' entries of it read and written again.
    forward_bytes_per_sub_step_ =
        4.0 * static_cast<double>(hybrid.column.size() + hybrid.value.size() + hybrid.overflow_row.size() +
                                  hybrid.overflow_start.size() + hybrid.overflow_column.size() +
                                  hybrid.overflow_value.size() + 2 * hybrid.overflow_row.size() + 2 * un);
    forward_column_ = upload_buffer(compute, "forward Euler ELL columns", hybrid.column, kRead, false);
    forward_value_ = upload_buffer(compute, "forward Euler ELL values", hybrid.value, kRead, false);
    forward_overflow_row_ = upload_buffer(compute, "forward Euler overflow rows", hybrid.overflow_row, kRead, false);
    forward_overflow_start_ =
        upload_buffer(compute, "forward Euler overflow row starts", hybrid.overflow_start, kRead, false);
    forward_overflow_column_ =
        upload_buffer(compute, "forward Euler overflow columns", hybrid.overflow_column, kRead, false);
    forward_overflow_value_ =
        upload_buffer(compute, "forward Euler overflow values", hybrid.overflow_value, kRead, false);
    // Read only by the planted fault no-decay-substep (see pheromone_forward_substep).
    decay_rate_ = upload_buffer(compute, "decay rate", to_float(params.decay_rate), kRead, false);
  }
  mass_ = upload_buffer(compute, "vertex mass", to_float(domain.vertex_mass), kRead, false);
  inverse_mass_ = upload_buffer(compute, "inverse vertex mass", to_float(inverse_mass), kRead, false);
  u_ = allocate_buffer(compute, "concentration", field_bytes, CL_MEM_READ_WRITE, true);
  scratch_ = allocate_buffer(compute, "concentration scratch", field_bytes, CL_MEM_READ_WRITE, true);
  fill(0.0);

  if (integrator == Integrator::BackwardEuler) {
    // Eq. 7: [M + dt (R_dif L + R_dec M)] u' = M u. With a varying R_dif the matrix is not symmetric,
    // and CG needs a symmetric positive definite system, so:
    //  * a vertex with r_dif,i > 0 ("active") has its row divided by r_dif,i:
    //      m_i (1 + dt r_dec,i) / r_dif,i u'_i + dt sum_j L_ij u'_j = m_i u_i / r_dif,i,
    //    whose matrix diag(m (1 + dt r_dec) / r_dif) + dt L is symmetric (L is) and positive definite
    //    (positive diagonal plus a PSD Laplacian). A uniform R_dif is the special case of one scale.
    //  * a vertex with r_dif,i = 0 does not diffuse: u'_i = u_i / (1 + dt r_dec,i), known up front, so
    //    its row becomes the identity and its column's terms in active rows move to the right-hand
    //    side (-dt L_ij u_j / (1 + dt r_dec,j)). Keeping only active-active couplings keeps S symmetric.
    // So S x = B u with S SPD (same sparsity as L) and B = the right-hand-side operator.
    std::vector<char> active(un);
    bool any_active = false;
    for (size_t i = 0; i < un; ++i) any_active |= (active[i] = params.diffuse_rate[i] > 0.0);
    diagonal_only_ = !any_active;
    HostCsr S, B;
    std::vector<double> inverse_diagonal(un, 1.0);
    for (int i = 0; i < n; ++i) {
      const double m = domain.vertex_mass[i];
      const double keep = 1.0 + time_step * params.decay_rate[i];
      if (!active[i]) {
        S.add(i, 1.0);
        B.add(i, 1.0 / keep);
      } else {
        const double r = params.diffuse_rate[i];
        double diagonal = m * keep / r;
        for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
          const int j = L.column[k];
          if (j == i) diagonal += time_step * L.value[k];
        }
        for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
          const int j = L.column[k];
          if (j == i) S.add(i, diagonal);
          else if (active[j]) S.add(j, time_step * L.value[k]);
        }
        if (std::none_of(S.column.begin() + S.row_start.back(), S.column.end(), [i](int c) { return c == i; }))
          S.add(i, diagonal);  // a Laplacian row without a stored diagonal entry
        inverse_diagonal[i] = 1.0 / diagonal;
        B.add(i, m / r);
        for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
          const int j = L.column[k];
          if (j != i && !active[j]) B.add(j, -time_step * L.value[k] / (1.0 + time_step * params.decay_rate[j]));
        }
      }
      S.end_row();
      B.end_row();
    }
    rhs_row_start_ = upload_buffer(compute, "backward Euler rhs row starts", B.row_start, kRead, false);
    rhs_column_ = upload_buffer(compute, "backward Euler rhs columns", B.column, kRead, false);
    rhs_value_ = upload_buffer(compute, "backward Euler rhs values", to_float(B.value), kRead, false);
    if (!diagonal_only_) {
      system_row_start_ = upload_buffer(compute, "backward Euler system row starts", S.row_start, kRead, false);
      system_column_ = upload_buffer(compute, "backward Euler system columns", S.column, kRead, false);
      system_value_ = upload_buffer(compute, "backward Euler system values", to_float(S.value), kRead, false);
      inverse_diagonal_ = upload_buffer(compute, "Jacobi preconditioner", to_float(inverse_diagonal), kRead, false);
      b_ = allocate_buffer(compute, "CG right-hand side", field_bytes, CL_MEM_READ_WRITE, true);
      r_ = allocate_buffer(compute, "CG residual", field_bytes, CL_MEM_READ_WRITE, true);
      z_ = allocate_buffer(compute, "CG preconditioned residual", field_bytes, CL_MEM_READ_WRITE, true);
      p_ = allocate_buffer(compute, "CG direction", field_bytes, CL_MEM_READ_WRITE, true);
      q_ = allocate_buffer(compute, "CG S times direction", field_bytes, CL_MEM_READ_WRITE, true);
      partials_ = allocate_buffer(compute, "CG partial sums", group_count_ * sizeof(cl_float4), CL_MEM_READ_WRITE, true);
      cg_state_ = allocate_buffer(compute, "CG state", sizeof(PhysarumCgState), CL_MEM_READ_WRITE, true);
    }
  }

  statistics_ = std::make_unique<DeviceFieldStatistics>(compute, mass_.buffer, n);
}

// ---- the field ----

std::vector<double> OpenCLPheromone::concentration() const {
  std::vector<float> u(static_cast<size_t>(vertex_count_));
  try {
    compute_.queue.enqueueReadBuffer(u_.buffer, CL_TRUE, 0, u_.payload_bytes, u.data());
  } catch (const cl::Error& e) {
    throw device_error("reading the pheromone field back from " + compute_.device.device_name, e.err());
  }
  return std::vector<double>(u.begin(), u.end());
}

void OpenCLPheromone::set_concentration(const std::vector<double>& u) {
  if (u.size() != static_cast<size_t>(vertex_count_))
    throw InputError("opencl pheromone: set_concentration got " + std::to_string(u.size()) + " values for " +
                     std::to_string(vertex_count_) + " vertices");
  const std::vector<float> f = to_float(u);
  compute_.queue.enqueueWriteBuffer(u_.buffer, CL_TRUE, 0, u_.payload_bytes, f.data());
}

void OpenCLPheromone::fill(double value) {
  compute_.queue.enqueueFillBuffer(u_.buffer, static_cast<float>(value), 0, u_.payload_bytes);
}

void OpenCLPheromone::add_deposits(const std::vector<double>& amount_per_vertex) {
  if (amount_per_vertex.size() != static_cast<size_t>(vertex_count_))
    throw InputError("opencl pheromone: add_deposits got " + std::to_string(amount_per_vertex.size()) +
                     " values for " + std::to_string(vertex_count_) + " vertices");
  const std::vector<float> amount = to_float(amount_per_vertex);
  if (!amount_.guarded) amount_ = allocate_buffer(compute_, "deposit amounts", u_.payload_bytes, CL_MEM_READ_ONLY, true);
  compute_.queue.enqueueWriteBuffer(amount_.buffer, CL_FALSE, 0, amount_.payload_bytes, amount.data());
  cl::Kernel& k = kernels_->add_amounts;
  set_arguments(k, static_cast<cl_uint>(vertex_count_), amount_, inverse_mass_, u_);
  compute_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(group_count_ * group_), cl::NDRange(group_));
  compute_.queue.finish();  // `amount` is a host temporary the non-blocking write reads from
}

const cl::Buffer& OpenCLPheromone::concentration_buffer() const { return u_.buffer; }
const cl::Buffer& OpenCLPheromone::mass_buffer() const { return mass_.buffer; }

// ---- time ----

void OpenCLPheromone::step() {
  try {
    if (integrator_ == Integrator::ForwardEuler) forward_step();
    else if (diagonal_only_) diagonal_step();
    else backward_step();
  } catch (const cl::Error& e) {
    throw device_error("pheromone step on " + compute_.device.device_name, e.err());
  }
}

void OpenCLPheromone::forward_step() {
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
  }
  if (from != &u_.buffer) compute_.queue.enqueueCopyBuffer(scratch_.buffer, u_.buffer, 0, 0, u_.payload_bytes);
}

void OpenCLPheromone::diagonal_step() {
  cl::Kernel& k = kernels_->csr_multiply;
  set_arguments(k, static_cast<cl_uint>(vertex_count_), rhs_row_start_, rhs_column_, rhs_value_, u_, scratch_);
  compute_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(group_count_ * group_), cl::NDRange(group_));
  compute_.queue.enqueueCopyBuffer(scratch_.buffer, u_.buffer, 0, 0, u_.payload_bytes);
  last_solve_ = {};
}

void OpenCLPheromone::backward_step() {
  Kernels& k = *kernels_;
  const cl_uint n = static_cast<cl_uint>(vertex_count_);
  const cl_uint groups = static_cast<cl_uint>(group_count_);
  const cl::NDRange global(group_count_ * group_), local(group_), single(final_group_);
  const cl::LocalSpaceArg scratch = cl::Local(group_ * sizeof(cl_float4));
  const cl::LocalSpaceArg final_scratch = cl::Local(final_group_ * sizeof(cl_float4));
  cl::CommandQueue& queue = compute_.queue;

  // b = B u
  set_arguments(k.csr_multiply, n, rhs_row_start_, rhs_column_, rhs_value_, u_, b_);
  queue.enqueueNDRangeKernel(k.csr_multiply, cl::NullRange, global, local);

  // x = u (the previous field: a good first guess, and the solution is written in place).
  const cl::Buffer& x = u_.buffer;
  set_arguments(k.cg_start, n, system_row_start_, system_column_, system_value_, inverse_diagonal_, b_, x, r_, z_, p_,
                partials_, scratch);
  queue.enqueueNDRangeKernel(k.cg_start, cl::NullRange, global, local);
  const double tolerance = options_.cg_relative_tolerance;
  set_arguments(k.cg_start_finish, groups, partials_, static_cast<cl_float>(tolerance * tolerance), cg_state_,
                final_scratch);
  queue.enqueueNDRangeKernel(k.cg_start_finish, cl::NullRange, single, single);

  set_arguments(k.cg_multiply, n, system_row_start_, system_column_, system_value_, p_, q_, cg_state_, partials_,
                scratch);
  for (cl::Kernel* finish : {&k.cg_alpha, &k.cg_beta}) set_arguments(*finish, groups, partials_, cg_state_, final_scratch);
  set_arguments(k.cg_update, n, inverse_diagonal_, p_, q_, x, r_, z_, cg_state_, partials_, scratch);
  set_arguments(k.cg_direction, n, z_, p_, cg_state_);

  PhysarumCgState state{};
  queue.enqueueReadBuffer(cg_state_.buffer, CL_TRUE, 0, sizeof state, &state);
  int enqueued = 0;
  while (state.status == PHYSARUM_CG_RUNNING && enqueued < options_.cg_max_iterations) {
    const int batch = std::min(options_.cg_check_interval, options_.cg_max_iterations - enqueued);
    for (int it = 0; it < batch; ++it) {
      queue.enqueueNDRangeKernel(k.cg_multiply, cl::NullRange, global, local);
      queue.enqueueNDRangeKernel(k.cg_alpha, cl::NullRange, single, single);
      queue.enqueueNDRangeKernel(k.cg_update, cl::NullRange, global, local);
      queue.enqueueNDRangeKernel(k.cg_beta, cl::NullRange, single, single);
      queue.enqueueNDRangeKernel(k.cg_direction, cl::NullRange, global, local);
    }
    enqueued += batch;
    queue.enqueueReadBuffer(cg_state_.buffer, CL_TRUE, 0, sizeof state, &state);
  }
  last_solve_.iterations = state.iterations;
  last_solve_.relative_residual = state.bb > 0.0f ? std::sqrt(double(state.rr) / double(state.bb)) : 0.0;
  last_solve_.converged = state.status == PHYSARUM_CG_CONVERGED;
  // A solve that stalls just above the tolerance (float rounding) still gives a usable field; one that
  // ends far from it does not, and must not pass silently.
  if (!last_solve_.converged && !(last_solve_.relative_residual <= 1e3 * tolerance))
    throw DeviceError("opencl pheromone: backward Euler conjugate gradients stopped after " +
                      std::to_string(state.iterations) + " iterations with relative residual " +
                      std::to_string(last_solve_.relative_residual) + " (tolerance " + std::to_string(tolerance) +
                      (state.status == PHYSARUM_CG_BREAKDOWN ? ", breakdown: p.Sp <= 0" : "") + ")");
}

// ---- summaries ----

double OpenCLPheromone::total_amount() const { return statistics_->weighted_sum(u_.buffer); }

FieldStatistics OpenCLPheromone::statistics(double U) const { return statistics_->compute(u_.buffer, U); }

std::vector<std::string> OpenCLPheromone::damaged_canaries() const {
  std::vector<std::string> damaged = statistics_->damaged_canaries();
  for (const DeviceBuffer* b : {&u_, &scratch_, &amount_, &b_, &r_, &z_, &p_, &q_, &partials_, &cg_state_})
    if (!canary_intact(compute_, *b)) damaged.push_back(b->name);
  return damaged;
}

}  // namespace physarum::opencl
