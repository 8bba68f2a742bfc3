#include "opencl/conjugate_gradients.hpp"

#include "common/base/errors.hpp"
#include "kernels/device_types.h"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/kernel_sources.hpp"
#include "opencl/runtime/opencl_error.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "opencl/runtime/work_group_size.hpp"

#include <algorithm>
#include <cmath>

namespace physarum::opencl {

static_assert(sizeof(PhysarumCgState) == 32, "PhysarumCgState: eight 4-byte fields on host and device");

struct DeviceConjugateGradients::Kernels {
  cl::Kernel start, start_finish, multiply, alpha, update, beta, direction;
};

DeviceConjugateGradients::~DeviceConjugateGradients() = default;

DeviceConjugateGradients::DeviceConjugateGradients(const ComputeContext& compute, const CsrMatrix& system,
                                                   const std::vector<double>& inverse_diagonal,
                                                   const ConjugateGradientOptions& options,
                                                   const std::string& build_options)
    : compute_(compute), options_(options), n_(system.rows) {
  kernels_ = std::make_unique<Kernels>();
  try {
    const cl::Program program = build_program(compute.context, compute.device, "conjugate_gradients.cl",
                                              kernel_source("conjugate_gradients.cl"), build_options);
    Kernels& k = *kernels_;
    k.start = cl::Kernel(program, "cg_start");
    k.start_finish = cl::Kernel(program, "cg_start_finish");
    k.multiply = cl::Kernel(program, "cg_multiply");
    k.alpha = cl::Kernel(program, "cg_alpha");
    k.update = cl::Kernel(program, "cg_update");
    k.beta = cl::Kernel(program, "cg_beta");
    k.direction = cl::Kernel(program, "cg_direction");
    // One local size for every per-vertex kernel, so all reductions have the same number of
    // partials; the smallest the kernels allow.
    group_ = common_work_group_size({&k.start, &k.multiply, &k.update, &k.direction}, compute.device, 256,
                                    sizeof(cl_float4));
    final_group_ = common_work_group_size({&k.start_finish, &k.alpha, &k.beta}, compute.device, 256, sizeof(cl_float4));
  } catch (const cl::Error& e) {
    throw device_error("preparing the conjugate-gradient kernels (conjugate_gradients.cl) on " +
                           compute.device.device_name,
                       e.err());
  }
  const size_t un = static_cast<size_t>(n_);
  group_count_ = padded_global_size(un, group_) / group_;
  constexpr cl_mem_flags kRead = CL_MEM_READ_ONLY;
  row_start_ = upload_buffer(compute, "backward Euler system row starts", system.row_start, kRead, false);
  column_ = upload_buffer(compute, "backward Euler system columns", system.column, kRead, false);
  value_ = upload_buffer(compute, "backward Euler system values",
                         std::vector<float>(system.value.begin(), system.value.end()), kRead, false);
  inverse_diagonal_ = upload_buffer(compute, "Jacobi preconditioner",
                                    std::vector<float>(inverse_diagonal.begin(), inverse_diagonal.end()), kRead, false);
  b_ = allocate_written<cl_float>(compute, "CG right-hand side", un);
  r_ = allocate_written<cl_float>(compute, "CG residual", un);
  z_ = allocate_written<cl_float>(compute, "CG preconditioned residual", un);
  p_ = allocate_written<cl_float>(compute, "CG direction", un);
  q_ = allocate_written<cl_float>(compute, "CG S times direction", un);
  partials_ = allocate_written<cl_float4>(compute, "CG partial sums", group_count_);
  state_ = allocate_written<PhysarumCgState>(compute, "CG state", 1);
}

const ConjugateGradientReport& DeviceConjugateGradients::solve(const DeviceBuffer& x) {
  Kernels& k = *kernels_;
  const cl_uint n = static_cast<cl_uint>(n_);
  const cl_uint groups = static_cast<cl_uint>(group_count_);
  const cl::NDRange global(group_count_ * group_), local(group_), single(final_group_);
  const cl::LocalSpaceArg scratch = cl::Local(group_ * sizeof(cl_float4));
  const cl::LocalSpaceArg final_scratch = cl::Local(final_group_ * sizeof(cl_float4));
  cl::CommandQueue& queue = compute_.queue;
  const double tolerance = options_.relative_tolerance;

  set_arguments(k.start, n, row_start_, column_, value_, inverse_diagonal_, b_, x, r_, z_, p_, partials_, scratch);
  queue.enqueueNDRangeKernel(k.start, cl::NullRange, global, local);
  set_arguments(k.start_finish, groups, partials_, static_cast<cl_float>(tolerance * tolerance), state_,
                final_scratch);
  queue.enqueueNDRangeKernel(k.start_finish, cl::NullRange, single, single);

  set_arguments(k.multiply, n, row_start_, column_, value_, p_, q_, state_, partials_, scratch);
  for (cl::Kernel* finish : {&k.alpha, &k.beta}) set_arguments(*finish, groups, partials_, state_, final_scratch);
  set_arguments(k.update, n, inverse_diagonal_, p_, q_, x, r_, z_, state_, partials_, scratch);
  set_arguments(k.direction, n, z_, p_, state_);

  PhysarumCgState state{};
  queue.enqueueReadBuffer(state_.buffer, CL_TRUE, 0, sizeof state, &state);
  int enqueued = 0;
  while (state.status == PHYSARUM_CG_RUNNING && enqueued < options_.max_iterations) {
    const int batch = std::min(options_.check_interval, options_.max_iterations - enqueued);
    for (int it = 0; it < batch; ++it) {
      queue.enqueueNDRangeKernel(k.multiply, cl::NullRange, global, local);
      queue.enqueueNDRangeKernel(k.alpha, cl::NullRange, single, single);
      queue.enqueueNDRangeKernel(k.update, cl::NullRange, global, local);
      queue.enqueueNDRangeKernel(k.beta, cl::NullRange, single, single);
      queue.enqueueNDRangeKernel(k.direction, cl::NullRange, global, local);
    }
    enqueued += batch;
    queue.enqueueReadBuffer(state_.buffer, CL_TRUE, 0, sizeof state, &state);
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
  return last_solve_;
}

std::vector<std::string> DeviceConjugateGradients::damaged_canaries() const {
  std::vector<std::string> damaged;
  for (const DeviceBuffer* b : {&b_, &r_, &z_, &p_, &q_, &partials_, &state_})
    if (!canary_intact(compute_, *b)) damaged.push_back(b->name);
  return damaged;
}

}  // namespace physarum::opencl
