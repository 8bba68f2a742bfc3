#include "opencl/reaction_diffusion.hpp"

#include "common/base/errors.hpp"
#include "common/simulation/simulation_state.hpp"
#include "kernels/device_types.h"
#include "opencl/hybrid_matrix.hpp"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/kernel_sources.hpp"
#include "opencl/runtime/mapped_buffer.hpp"
#include "opencl/runtime/opencl_error.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "opencl/reaction_formula.hpp"
#include "opencl/runtime/work_group_size.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>

namespace physarum::opencl {

struct OpenCLReactionDiffusion::Kernels {
  cl::Kernel substep, overflow, imex_rhs, floors, copy_morphogen;
};


namespace {

const char* const kWho = "opencl reaction-diffusion";

bool uniform(const IntrinsicVertexData<double>& v) {
  return std::all_of(v.begin(), v.end(), [&](double x) { return x == v[0]; });
}

// Whether every row of K sums to zero up to its rounding (|sum| <= 1e-9 sum |K_ij|): true of a
// diffusion operator with no-flux boundaries, which leaves constants alone. Far below float's
// resolution, so dropping such a remainder changes no float result.
bool rows_sum_to_zero(const CsrMatrix& K) {
  for (int i = 0; i < K.rows; ++i) {
    double sum = 0.0, size = 0.0;
    for (int e = K.row_start[i]; e < K.row_start[i + 1]; ++e) {
      sum += K.value[e];
      size += std::abs(K.value[e]);
    }
    if (std::abs(sum) > 1e-9 * size) return false;
  }
  return true;
}

// A's off-diagonal entries only, in their order.
CsrMatrix off_diagonal(const CsrMatrix& A) {
  CsrMatrix out;
  out.rows = A.rows;
  out.cols = A.cols;
  out.row_start.assign(1, 0);
  for (int i = 0; i < A.rows; ++i) {
    for (int e = A.row_start[i]; e < A.row_start[i + 1]; ++e) {
      if (A.column[e] == i) continue;
      out.column.push_back(A.column[e]);
      out.value.push_back(A.value[e]);
    }
    out.row_start.push_back(static_cast<int>(out.column.size()));
  }
  return out;
}

bool has_option(const std::string& options, const std::string& define) {
  return options.find("-D" + define) != std::string::npos;
}

constexpr cl_mem_flags kRead = CL_MEM_READ_ONLY;

}  // namespace

// What the constructor's steps hand on to each other: the kinetics as OpenCL C and the explicit
// sub-step's operator. Needed only while building.
struct OpenCLReactionDiffusion::Setup {
  std::vector<size_t> varying;  // coefficients read per vertex, in slot order
  std::string reactions, loads;
  bool shared_weights = false;
  std::string scales;  // c_m of K_m = c_m K_0, as literals (RD_WEIGHT_SCALES)
  std::vector<CsrMatrix> substep_matrices;
  bool zero_row_sums = false;
  int ell_width = PHYSARUM_ELL_WIDTH;
  std::string floors;
};

OpenCLReactionDiffusion::~OpenCLReactionDiffusion() = default;

OpenCLReactionDiffusion::OpenCLReactionDiffusion(const ComputeContext& compute, const SurfaceDomain& domain,
                                                 const ReactionDiffusionSystem& system,
                                                 const OpenCLReactionDiffusionOptions& options)
    : compute_(compute), options_(options), integrator_(system.integrator) {
  check_reaction_diffusion_system(system, domain.vertex_count, kWho);
  const int n = domain.vertex_count;
  const size_t un = static_cast<size_t>(n);
  vertex_count_ = n;
  morphogen_count_ = static_cast<int>(system.morphogens.size());
  const size_t M = static_cast<size_t>(morphogen_count_);
  time_step_ = system.time_step;
  substeps_ = system.substeps;
  sub_step_ = time_step_ / substeps_;
  mass_host_ = system.mass;
  stiffness_ = system.stiffness;
  fixed_host_ = system.fixed;
  has_fixed_ = std::any_of(fixed_host_.begin(), fixed_host_.end(), [](std::uint8_t f) { return f != 0; });
  if (fixed_host_.empty()) fixed_host_.assign(un, 0);
  // The planted fault rd-swap-diffusion in the IMEX systems (the explicit kernel swaps on its own).
  if (has_option(options.build_options, "PHYSARUM_FAULT_RD_SWAP_DIFFUSION") && integrator_ == Integrator::Imex)
    std::swap(stiffness_[0], stiffness_[1]);

  // In this order: each step needs the ones before it, and the device sees its calls and
  // allocations in the order it always has (the same buffers, the same bits).
  Setup setup;
  interleaved_ = integrator_ == Integrator::Forward && M >= 5;
  translate_kinetics(system, setup);
  find_shared_weights(system, setup);
  make_substep_matrices(system, setup);
  write_floors(system, setup);
  build_kernels(kernel_prelude(setup));
  choose_stride();
  upload_vertex_data(system, setup.varying);
  allocate_state(system);
  if (integrator_ == Integrator::Forward)
    upload_explicit_operator(setup);
  else
    make_imex_solvers(system);

  statistics_ = std::make_unique<DeviceFieldStatistics>(compute, mass_.buffer, n);
  for (size_t m = 0; m < M; ++m) set_field(system.initial[m], static_cast<int>(m));
}

void OpenCLReactionDiffusion::translate_kinetics(const ReactionDiffusionSystem& system, Setup& setup) {
  const size_t M = static_cast<size_t>(morphogen_count_);
  std::vector<size_t>& varying = setup.varying;
  std::map<std::string, std::string> names;
  for (size_t m = 0; m < M; ++m) names[system.morphogens[m]] = "rd_u[" + std::to_string(m) + "]";
  for (size_t c = 0; c < system.coefficient_names.size(); ++c) {
    if (uniform(system.coefficients[c]) && !system.coefficients[c].empty()) {
      names[system.coefficient_names[c]] = float_literal(system.coefficients[c][0]);
    } else {
      names[system.coefficient_names[c]] = "rd_c" + std::to_string(varying.size());
      varying.push_back(c);
    }
  }
  std::string& reactions = setup.reactions;
  for (size_t m = 0; m < M; ++m) {
    std::map<std::string, std::string> formula_names = names;
    // The planted fault rd-no-feed: Gray-Scott's feed term F (1 - u) dropped from the first formula.
    if (m == 0 && has_option(options_.build_options, "PHYSARUM_FAULT_RD_NO_FEED") && formula_names.count("F"))
      formula_names["F"] = "0.0f";
    translated_.push_back(translate_reaction_formula(system.reaction[m], formula_names,
                                                     std::string(kWho) + ": the reaction of morphogen '" +
                                                         system.morphogens[m] + "'"));
    reactions += "rd_r[" + std::to_string(m) + "] = " + translated_.back() + "; ";
  }
  std::string& loads = setup.loads;
  for (size_t slot = 0; slot < varying.size(); ++slot)
    loads += "const float rd_c" + std::to_string(slot) + " = coefficients[" + std::to_string(slot) + "u * stride + i]; ";
}

void OpenCLReactionDiffusion::find_shared_weights(const ReactionDiffusionSystem& system, Setup& setup) const {
  const size_t M = static_cast<size_t>(morphogen_count_);
  // Isotropic morphogens have stiffness D_m L: when every K_m is c_m K_0, the explicit sub-step
  // reads one set of weights for all of them and scales each morphogen's sum by c_m, a third fewer
  // bytes per vertex for two morphogens (bench_reaction_diffusion).
  std::vector<double> weight_scale(M, 1.0);
  bool& shared_weights = setup.shared_weights;
  shared_weights = integrator_ == Integrator::Forward;
  const std::vector<double>& K0 = system.stiffness[0].value;
  const auto reference = std::find_if(K0.begin(), K0.end(), [](double v) { return v != 0.0; });
  if (reference == K0.end()) shared_weights = false;
  for (size_t m = 1; m < M && shared_weights; ++m) {
    const std::vector<double>& Km = system.stiffness[m].value;
    const double c = Km[static_cast<size_t>(reference - K0.begin())] / *reference;
    for (size_t e = 0; e < K0.size() && shared_weights; ++e)
      shared_weights = std::abs(Km[e] - c * K0[e]) <= 1e-12 * std::max(std::abs(Km[e]), std::abs(c * K0[e]));
    weight_scale[m] = c;
  }
  std::string& scales = setup.scales;
  for (size_t m = 0; m < M; ++m) scales += (m ? ", " : "") + float_literal(weight_scale[m]);
}

void OpenCLReactionDiffusion::make_substep_matrices(const ReactionDiffusionSystem& system, Setup& setup) const {
  const int n = vertex_count_;
  const size_t M = static_cast<size_t>(morphogen_count_);
  // The explicit sub-step matrices W_m = -h M^-1 K_m, rows of held vertices zero. When every K_m's
  // rows sum to zero (diffusion: always, unless a caller's stiffness says otherwise) only their
  // off-diagonal entries go to the device (RD_ZERO_ROW_SUMS in reaction_diffusion.cl); the ELL width
  // is the narrowest that holds 97 % of the rows whole (opencl/hybrid_matrix.hpp).
  std::vector<CsrMatrix>& substep_matrices = setup.substep_matrices;
  bool& zero_row_sums = setup.zero_row_sums;
  zero_row_sums = integrator_ == Integrator::Forward;
  int& ell_width = setup.ell_width;
  ell_width = PHYSARUM_ELL_WIDTH;
  if (integrator_ == Integrator::Forward) {
    for (size_t m = 0; m < M; ++m) {
      zero_row_sums = zero_row_sums && rows_sum_to_zero(system.stiffness[m]);
      CsrMatrix W = system.stiffness[m];
      for (int i = 0; i < n; ++i)
        for (int e = W.row_start[i]; e < W.row_start[i + 1]; ++e)
          W.value[e] = fixed_host_[i] ? 0.0 : -sub_step_ * W.value[e] / system.mass[i];
      substep_matrices.push_back(std::move(W));
    }
    if (zero_row_sums)
      for (CsrMatrix& W : substep_matrices) W = off_diagonal(W);
    ell_width = ell_width_for(substep_matrices[0], PHYSARUM_ELL_WIDTH, 0.03);
  }
}

void OpenCLReactionDiffusion::write_floors(const ReactionDiffusionSystem& system, Setup& setup) {
  const size_t M = static_cast<size_t>(morphogen_count_);
  // The floors, as literals: -INFINITY for a morphogen without one.
  std::string& floors = setup.floors;
  for (size_t m = 0; m < M; ++m) {
    const bool floored = !system.minimum.empty() && std::isfinite(system.minimum[m]);
    has_floors_ = has_floors_ || floored;
    floors += std::string(m ? ", " : "") + (floored ? float_literal(system.minimum[m]) : "-INFINITY");
  }
}

std::string OpenCLReactionDiffusion::kernel_prelude(const Setup& setup) const {
  const size_t M = static_cast<size_t>(morphogen_count_);
  return "#define RD_FLOORS {" + setup.floors + "}\n#define RD_MORPHOGENS " + std::to_string(M) +
         "\n#define RD_LOAD_COEFFICIENTS " + setup.loads + "\n#define RD_REACTIONS " + setup.reactions + "\n" +
         (has_fixed_ ? "#define RD_HAS_FIXED\n" : "") +
         (setup.shared_weights ? "#define RD_SHARED_WEIGHTS\n#define RD_WEIGHT_SCALES {" + setup.scales + "}\n" : "") +
         "#define RD_ELL_WIDTH " + std::to_string(setup.ell_width) + "\n" +
         (setup.zero_row_sums ? "#define RD_ZERO_ROW_SUMS\n" : "") + (interleaved_ ? "#define RD_INTERLEAVED\n" : "");
}

void OpenCLReactionDiffusion::build_kernels(const std::string& prelude) {
  kernels_ = std::make_unique<Kernels>();
  try {
    const cl::Program program = build_program(compute_.context, compute_.device, "reaction_diffusion.cl",
                                              prelude + kernel_source("reaction_diffusion.cl"), options_.build_options);
    kernels_->substep = cl::Kernel(program, "rd_explicit_substep");
    kernels_->overflow = cl::Kernel(program, "rd_explicit_overflow");
    kernels_->imex_rhs = cl::Kernel(program, "rd_imex_rhs");
    kernels_->floors = cl::Kernel(program, "rd_apply_floors");
    kernels_->copy_morphogen = cl::Kernel(program, "rd_copy_morphogen");
    group_ = common_work_group_size({&kernels_->substep, &kernels_->overflow, &kernels_->imex_rhs, &kernels_->floors},
                                    compute_.device, 256);
  } catch (const cl::Error& e) {
    throw device_error("preparing the reaction-diffusion kernels (reaction_diffusion.cl) on " +
                           compute_.device.device_name,
                       e.err());
  }
}

void OpenCLReactionDiffusion::choose_stride() {
  const size_t un = static_cast<size_t>(vertex_count_);
  // Morphogen blocks start on the device's sub-buffer alignment, so each can be a sub-buffer.
  const size_t align_floats =
      std::max<size_t>(1, compute_.device.device.getInfo<CL_DEVICE_MEM_BASE_ADDR_ALIGN>() / (8 * sizeof(cl_float)));
  const size_t unit = std::max(group_, align_floats);
  stride_ = (un + unit - 1) / unit * unit;
}

void OpenCLReactionDiffusion::upload_vertex_data(const ReactionDiffusionSystem& system,
                                                 const std::vector<size_t>& varying) {
  const size_t un = static_cast<size_t>(vertex_count_);
  std::vector<float> coefficient_values(std::max<size_t>(1, varying.size() * stride_), 0.0f);
  for (size_t slot = 0; slot < varying.size(); ++slot)
    for (size_t i = 0; i < un; ++i)
      coefficient_values[slot * stride_ + i] = static_cast<float>(system.coefficients[varying[slot]][i]);
  coefficients_ = upload_buffer(compute_, "reaction coefficients", coefficient_values, kRead, false);
  fixed_ = upload_buffer(compute_, "held vertices", has_fixed_ ? fixed_host_ : std::vector<std::uint8_t>(1, 0), kRead,
                         false);
  std::vector<float> mass(stride_, 0.0f);
  for (size_t i = 0; i < un; ++i) mass[i] = static_cast<float>(system.mass[i]);
  mass_ = upload_buffer(compute_, "vertex mass", mass, kRead, false);
}

void OpenCLReactionDiffusion::allocate_state(const ReactionDiffusionSystem& system) {
  const size_t un = static_cast<size_t>(vertex_count_);
  const size_t M = static_cast<size_t>(morphogen_count_);
  // Two halves of the state for the explicit integrator's double buffer, one for IMEX.
  const size_t halves = integrator_ == Integrator::Forward ? 2 : 1;
  for (size_t half = 0; half < halves; ++half) {
    DeviceBuffer& u = state_[half];
    // An interleaved state ends in 8 - M spare floats: the sub-step loads a vertex's values as eight
    // floats (RD_GATHER in kernels/reaction_diffusion.cl), the last vertex's too.
    const size_t spare = interleaved_ ? 8 - M : 0;
    u = allocate_written<cl_float>(compute_, half == 0 ? "morphogens" : "morphogens (second half)",
                                   M * stride_ + spare);
    compute_.queue.enqueueFillBuffer(u.buffer, 0.0f, 0, u.payload_bytes);
    for (size_t m = 0; m < M && !interleaved_; ++m) {
      cl_buffer_region region{m * stride_ * sizeof(cl_float), un * sizeof(cl_float)};
      DeviceBuffer view;
      view.buffer = u.buffer.createSubBuffer(CL_MEM_READ_WRITE, CL_BUFFER_CREATE_TYPE_REGION, &region);
      view.name = "morphogen '" + system.morphogens[m] + "'";
      view.payload_bytes = region.size;
      state_views_[half].push_back(view);
    }
  }
  if (interleaved_) lane_ = allocate_written<cl_float>(compute_, "one morphogen (copied out)", stride_);
}

const DeviceBuffer& OpenCLReactionDiffusion::morphogen_block(int morphogen) const {
  if (!interleaved_) return state_view(morphogen);
  set_arguments(kernels_->copy_morphogen, static_cast<cl_uint>(vertex_count_), static_cast<cl_uint>(stride_),
                static_cast<cl_uint>(morphogen), state(), lane_);
  compute_.queue.enqueueNDRangeKernel(kernels_->copy_morphogen, cl::NullRange, cl::NDRange(stride_), cl::NDRange(group_));
  return lane_;
}

std::vector<float> OpenCLReactionDiffusion::read_state() const {
  std::vector<float> all(static_cast<size_t>(morphogen_count_) * static_cast<size_t>(vertex_count_));
  compute_.queue.enqueueReadBuffer(state().buffer, CL_TRUE, 0, all.size() * sizeof(cl_float), all.data());
  return all;
}

void OpenCLReactionDiffusion::write_morphogen(int morphogen, const std::vector<float>& values) {
  const auto M = static_cast<size_t>(morphogen_count_);
  if (!interleaved_) {
    compute_.queue.enqueueWriteBuffer(state().buffer, CL_TRUE, static_cast<size_t>(morphogen) * stride_ * sizeof(cl_float),
                                      values.size() * sizeof(cl_float), values.data());
    return;
  }
  std::vector<float> all = read_state();
  for (size_t i = 0; i < values.size(); ++i) all[i * M + static_cast<size_t>(morphogen)] = values[i];
  compute_.queue.enqueueWriteBuffer(state().buffer, CL_TRUE, 0, all.size() * sizeof(cl_float), all.data());
}

void OpenCLReactionDiffusion::upload_explicit_operator(const Setup& setup) {
  const size_t un = static_cast<size_t>(vertex_count_);
  const size_t M = static_cast<size_t>(morphogen_count_);
  const bool shared_weights = setup.shared_weights;
  // W_m in hybrid form with one ELL row per padded row.
  std::vector<HybridMatrix> hybrid;
  for (size_t m = 0; m < M; ++m)
    hybrid.push_back(to_hybrid(setup.substep_matrices[m], static_cast<int>(stride_), setup.ell_width));
  // Each ELL slot's column beside morphogen 0's weight (its bits), one 8-byte pair per slot and
  // row (kernels/reaction_diffusion.cl says why); then a block of weights for each other
  // morphogen, none when the weights are shared.
  // An interleaved state's columns are stored as the offset of the neighbour's first value (column
  // times M: RD_SLOT_INDEX in the kernel), which must fit the kernel's 32-bit column.
  const HybridMatrix& shape = hybrid[0];
  const size_t column_scale = interleaved_ ? M : 1;
  if (column_scale * stride_ > static_cast<size_t>(std::numeric_limits<cl_int>::max()))
    throw InputError("opencl reaction-diffusion: " + std::to_string(un) + " vertices with " + std::to_string(M) +
                     " morphogens exceed the explicit sub-step's 32-bit offsets (at most " +
                     std::to_string(std::numeric_limits<cl_int>::max() / column_scale) +
                     " padded vertices); use \"integrator\": \"imex\" or a coarser surface");
  std::vector<cl_int> column_weight(2 * shape.column.size());
  for (size_t e = 0; e < shape.column.size(); ++e) {
    column_weight[2 * e] = static_cast<cl_int>(static_cast<size_t>(shape.column[e]) * column_scale);
    std::memcpy(&column_weight[2 * e + 1], &shape.value[e], sizeof(cl_float));
  }
  std::vector<float> values, overflow_values;
  for (size_t m = 0; m < (shared_weights ? 1 : M); ++m) {
    if (m > 0) values.insert(values.end(), hybrid[m].value.begin(), hybrid[m].value.end());
    overflow_values.insert(overflow_values.end(), hybrid[m].overflow_value.begin(), hybrid[m].overflow_value.end());
  }
  if (values.empty()) values.push_back(0.0f);  // a buffer may not be empty
  const double weight_blocks = shared_weights ? 1.0 : static_cast<double>(M);
  overflow_rows_ = shape.overflow_rows();
  overflow_entries_ = static_cast<int>(shape.overflow_column.size());
  if (overflow_values.empty()) overflow_values.push_back(0.0f);  // a buffer may not be empty
  auto non_empty = [](std::vector<int> v) { return v.empty() ? std::vector<int>{0} : v; };
  column_ = upload_buffer(compute_, "reaction-diffusion ELL columns and weights", column_weight, kRead, false);
  value_ = upload_buffer(compute_, "reaction-diffusion ELL weights of morphogens 1..", values, kRead, false);
  overflow_row_ = upload_buffer(compute_, "reaction-diffusion overflow rows", non_empty(shape.overflow_row), kRead, false);
  overflow_start_ = upload_buffer(compute_, "reaction-diffusion overflow starts", shape.overflow_start, kRead, false);
  overflow_column_ =
      upload_buffer(compute_, "reaction-diffusion overflow columns", non_empty(shape.overflow_column), kRead, false);
  overflow_value_ = upload_buffer(compute_, "reaction-diffusion overflow values", overflow_values, kRead, false);
  const double ell = static_cast<double>(shape.column.size());
  bytes_per_sub_step_ = 4.0 * (ell * (1.0 + weight_blocks) +
                               static_cast<double>(shape.overflow_row.size() + shape.overflow_start.size()) +
                               static_cast<double>(overflow_entries_) * (1.0 + weight_blocks) +
                               2.0 * static_cast<double>(M) * static_cast<double>(overflow_rows_) +
                               2.0 * static_cast<double>(M * un) + static_cast<double>(setup.varying.size() * un)) +
                        (has_fixed_ ? static_cast<double>(un) : 0.0);
}

void OpenCLReactionDiffusion::make_imex_solvers(const ReactionDiffusionSystem& system) {
  const int n = vertex_count_;
  const size_t un = static_cast<size_t>(n);
  const size_t M = static_cast<size_t>(morphogen_count_);
  imex_solver_ = options_.imex_solver;
  if (imex_solver_ == ImexSolver::Automatic)
    imex_solver_ =
        implicit_solve_on_host(compute_.device, n) ? ImexSolver::HostFactorization : ImexSolver::DeviceConjugateGradients;
  rhs_ = allocate_written<cl_float>(compute_, "IMEX right-hand sides", M * stride_);
  coupling_ = has_fixed_ ? allocate_written<cl_float>(compute_, "Dirichlet coupling", M * stride_)
                         : allocate_written<cl_float>(compute_, "Dirichlet coupling", 1);
  if (imex_solver_ == ImexSolver::HostFactorization && has_fixed_) held_solution_.resize(un);
  for (size_t m = 0; m < M; ++m) {
    // S = M + h K_m with the held vertices' rows and columns replaced by m_i on the diagonal.
    const CsrMatrix& K = stiffness_[m];
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < n; ++i) {
      if (fixed_host_[i]) {
        entries.emplace_back(i, i, system.mass[i]);
        continue;
      }
      entries.emplace_back(i, i, system.mass[i]);
      for (int e = K.row_start[i]; e < K.row_start[i + 1]; ++e)
        if (!fixed_host_[K.column[e]]) entries.emplace_back(i, K.column[e], sub_step_ * K.value[e]);
    }
    Eigen::SparseMatrix<double, Eigen::RowMajor> S(n, n);
    S.setFromTriplets(entries.begin(), entries.end());
    if (imex_solver_ == ImexSolver::HostFactorization) {
      host_solvers_.push_back(std::make_unique<HostCholeskySolve>(
          CsrMatrix::from_eigen(S), FactorPrecision::Double, std::string(kWho) + ": the IMEX system of '" + system.morphogens[m] +
                                        "' (a stiffness matrix that is not positive semi-definite?)"));
    } else {
      std::vector<double> inverse_diagonal(un);
      for (int i = 0; i < n; ++i) inverse_diagonal[i] = 1.0 / S.coeff(i, i);
      solvers_.push_back(std::make_unique<DeviceConjugateGradients>(
          compute_, CsrMatrix::from_eigen(S), inverse_diagonal,
          ConjugateGradientOptions{options_.cg_relative_tolerance, options_.cg_max_iterations, options_.cg_check_interval},
          options_.build_options));
    }
  }
}

std::string OpenCLReactionDiffusion::device_name() const { return compute_.device.describe(); }

// ---- time ----

void OpenCLReactionDiffusion::step() {
  try {
    if (integrator_ == Integrator::Forward) explicit_step();
    else imex_step();
  } catch (const cl::Error& e) {
    throw device_error("reaction-diffusion step on " + compute_.device.device_name, e.err());
  }
  ++steps_taken_;
}

void OpenCLReactionDiffusion::run(long long steps) {
  for (long long s = 0; s < steps; ++s) step();
}

void OpenCLReactionDiffusion::finish() { compute_.queue.finish(); }

void OpenCLReactionDiffusion::explicit_step() {
  const cl::NDRange overflow_global(padded_global_size(static_cast<size_t>(overflow_rows_), group_));
  for (int s = 0; s < substeps_; ++s) {
    const DeviceBuffer& from = state();
    const DeviceBuffer& to = state_[static_cast<size_t>(1 - current_)];
    set_arguments(kernels_->substep, static_cast<cl_uint>(vertex_count_), static_cast<cl_uint>(stride_), column_, value_,
                  coefficients_, fixed_, static_cast<cl_float>(sub_step_), from, to);
    compute_.queue.enqueueNDRangeKernel(kernels_->substep, cl::NullRange, cl::NDRange(stride_), cl::NDRange(group_));
    if (overflow_rows_ > 0) {
      set_arguments(kernels_->overflow, static_cast<cl_uint>(overflow_rows_), static_cast<cl_uint>(stride_),
                    static_cast<cl_uint>(overflow_entries_), overflow_row_, overflow_start_, overflow_column_,
                    overflow_value_, from, to);
      compute_.queue.enqueueNDRangeKernel(kernels_->overflow, cl::NullRange, overflow_global, cl::NDRange(group_));
    }
    if (has_floors_) apply_floors(to.buffer);
    current_ = 1 - current_;
  }
}

void OpenCLReactionDiffusion::imex_step() {
  const size_t un = static_cast<size_t>(vertex_count_);
  for (int s = 0; s < substeps_; ++s) {
    set_arguments(kernels_->imex_rhs, static_cast<cl_uint>(vertex_count_), static_cast<cl_uint>(stride_), mass_,
                  coefficients_, fixed_, coupling_, static_cast<cl_float>(sub_step_), state(), rhs_);
    compute_.queue.enqueueNDRangeKernel(kernels_->imex_rhs, cl::NullRange, cl::NDRange(stride_), cl::NDRange(group_));
    if (imex_solver_ == ImexSolver::DeviceConjugateGradients) {
      for (int m = 0; m < morphogen_count_; ++m) {
        // x starts from the previous step's values: the warm start.
        compute_.queue.enqueueCopyBuffer(rhs_.buffer, solvers_[m]->right_hand_side().buffer,
                                         static_cast<size_t>(m) * stride_ * sizeof(cl_float), 0, un * sizeof(cl_float));
        last_solve_ = solvers_[m]->solve(state_view(m));
      }
      if (has_floors_) apply_floors(state().buffer);
      continue;
    }
    host_imex_solve();
    if (has_floors_) apply_floors(state().buffer);
    last_solve_ = {};
  }
}

// After the whole sub-step (the overflow rows included): a floor applied to a partial sum would not be
// the reference's floor of the value.
void OpenCLReactionDiffusion::apply_floors(const cl::Buffer& u) {
  set_arguments(kernels_->floors, static_cast<cl_uint>(vertex_count_), static_cast<cl_uint>(stride_), fixed_, u);
  compute_.queue.enqueueNDRangeKernel(kernels_->floors, cl::NullRange, cl::NDRange(stride_), cl::NDRange(group_));
}

// Every morphogen's system solved by its host factor on the right-hand sides and fields mapped in
// place: one wait for the queue (the second map; the right-hand side kernel runs before it) and no
// copies where the device's memory is the host's (opencl/runtime/mapped_buffer.hpp).
void OpenCLReactionDiffusion::host_imex_solve() {
  const size_t un = static_cast<size_t>(vertex_count_);
  const size_t all = static_cast<size_t>(morphogen_count_) * stride_;
  const MappedBuffer<float> b(compute_, rhs_, CL_MAP_READ, 0, all, false);
  const MappedBuffer<float> u(compute_, state(), CL_MAP_READ | CL_MAP_WRITE, 0, all);
  for (int m = 0; m < morphogen_count_; ++m) {
    const size_t offset = static_cast<size_t>(m) * stride_;
    if (!has_fixed_) {
      host_solvers_[static_cast<size_t>(m)]->solve(b.data() + offset, u.data() + offset);
      continue;
    }
    // The held values stay as they are: m_i u_i / m_i rounds, and a held value must not move at all.
    host_solvers_[static_cast<size_t>(m)]->solve(b.data() + offset, held_solution_.data());
    for (size_t i = 0; i < un; ++i)
      if (!fixed_host_[i]) u[offset + i] = held_solution_[i];
  }
}

// The held vertices' columns moved to the right-hand side: c_m,i = -h sum_{j held} (K_m)_ij u_m,j,
// for the rows that are not held. Recomputed whenever the held values may change (set/fill).
void OpenCLReactionDiffusion::update_dirichlet_coupling() {
  if (!has_fixed_ || integrator_ != Integrator::Imex) return;
  const size_t un = static_cast<size_t>(vertex_count_);
  std::vector<float> coupling(static_cast<size_t>(morphogen_count_) * stride_, 0.0f);
  for (int m = 0; m < morphogen_count_; ++m) {
    const IntrinsicVertexData<double> u = field_values(m);
    const CsrMatrix& K = stiffness_[m];
    for (size_t i = 0; i < un; ++i) {
      if (fixed_host_[i]) continue;
      double sum = 0.0;
      for (int e = K.row_start[i]; e < K.row_start[i + 1]; ++e)
        if (fixed_host_[K.column[e]]) sum += K.value[e] * u[K.column[e]];
      coupling[static_cast<size_t>(m) * stride_ + i] = static_cast<float>(-sub_step_ * sum);
    }
  }
  compute_.queue.enqueueWriteBuffer(coupling_.buffer, CL_TRUE, 0, coupling.size() * sizeof(float), coupling.data());
}

// ---- layers ----

void OpenCLReactionDiffusion::check_morphogen(int layer, const char* what) const {
  check_layer_index(layer, layer_count(), kWho, what);
}

int OpenCLReactionDiffusion::add_static_layer(const IntrinsicVertexData<double>& values) {
  const int index = layer_count();
  check_layer_values(values, vertex_count_, index, kWho, "add_static_layer");
  static_fields_.push_back(std::make_unique<OpenCLStaticField>(compute_, "static field layer " + std::to_string(index),
                                                               DeviceVertexData<double>(mass_host_.values()),
                                                               DeviceVertexData<double>(values.values())));
  return index;
}

IntrinsicVertexData<double> OpenCLReactionDiffusion::field_values(int layer) const {
  check_morphogen(layer, "field_values");
  if (layer >= morphogen_count_)
    return IntrinsicVertexData<double>(static_fields_[static_cast<size_t>(layer - morphogen_count_)]->concentration().values());
  std::vector<float> values(static_cast<size_t>(vertex_count_));
  compute_.queue.enqueueReadBuffer(morphogen_block(layer).buffer, CL_TRUE, 0, values.size() * sizeof(cl_float),
                                   values.data());
  return IntrinsicVertexData<double>(std::vector<double>(values.begin(), values.end()));
}

void OpenCLReactionDiffusion::set_field(const IntrinsicVertexData<double>& values, int layer) {
  check_morphogen(layer, "set_field");
  check_layer_values(values, vertex_count_, layer, kWho, "set_field");
  if (layer >= morphogen_count_) {
    static_fields_[static_cast<size_t>(layer - morphogen_count_)]->set_concentration(
        DeviceVertexData<double>(values.values()));
    return;
  }
  write_morphogen(layer, std::vector<float>(values.begin(), values.end()));
  update_dirichlet_coupling();
}

void OpenCLReactionDiffusion::fill_field(double value, int layer) {
  check_morphogen(layer, "fill_field");
  check_layer_value(value, layer, kWho, "fill_field");
  if (layer >= morphogen_count_) {
    static_fields_[static_cast<size_t>(layer - morphogen_count_)]->fill(value);
    return;
  }
  if (interleaved_) {
    write_morphogen(layer, std::vector<float>(static_cast<size_t>(vertex_count_), static_cast<cl_float>(value)));
  } else {
    compute_.queue.enqueueFillBuffer(state().buffer, static_cast<cl_float>(value),
                                     static_cast<size_t>(layer) * stride_ * sizeof(cl_float),
                                     static_cast<size_t>(vertex_count_) * sizeof(cl_float));
  }
  update_dirichlet_coupling();
}

FieldStatistics OpenCLReactionDiffusion::field_statistics(double U, int layer) const {
  check_morphogen(layer, "field_statistics");
  if (layer >= morphogen_count_) return static_fields_[static_cast<size_t>(layer - morphogen_count_)]->statistics(U);
  return statistics_->compute(morphogen_block(layer).buffer, U);
}

std::vector<std::string> OpenCLReactionDiffusion::damaged_canaries() const {
  std::vector<std::string> damaged = statistics_->damaged_canaries();
  for (const DeviceBuffer* b : {&state_[0], &state_[1], &rhs_, &coupling_, &lane_})
    if (b->guarded && !canary_intact(compute_, *b)) damaged.push_back(b->name);
  for (const auto& solver : solvers_)
    for (const std::string& name : solver->damaged_canaries()) damaged.push_back(name);
  for (const auto& field : static_fields_)
    for (const std::string& name : field->damaged_canaries()) damaged.push_back(name);
  return damaged;
}

SimulationState OpenCLReactionDiffusion::save_state() const {
  SimulationState state;
  state.steps_taken = steps_taken_;
  state.time = time();
  for (int layer = 0; layer < layer_count(); ++layer) state.layers.push_back(field_values(layer));
  return state;
}

void OpenCLReactionDiffusion::restore_state(const SimulationState& state) {
  check_state_fits(state, layer_count(), vertex_count_, 0, 0, kWho);
  for (int layer = 0; layer < layer_count(); ++layer) set_field(state.layers[static_cast<size_t>(layer)], layer);
  steps_taken_ = state.steps_taken;
}

}  // namespace physarum::opencl
