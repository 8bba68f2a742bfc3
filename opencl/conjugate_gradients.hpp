#pragma once
// Jacobi-preconditioned conjugate gradients for S x = b on the device (kernels/conjugate_gradients.cl),
// S symmetric positive definite: the backward Euler system of the pheromone field
// (common/model/pheromone_operators.hpp). The solver's scalars stay on the device; the host enqueues
// iterations in batches and reads only the 32-byte solver state between two batches.
#include "common/numerics/csr_matrix.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"

#include <memory>
#include <string>
#include <vector>

namespace physarum::opencl {

struct ConjugateGradientOptions {
  double relative_tolerance = 1e-6;  // stop when ||b - S x|| <= tolerance ||b||
  int max_iterations = 1000;         // a bound, so a solve always ends
  int check_interval = 16;           // iterations enqueued between two reads of the solver state
};

// What the last solve did.
struct ConjugateGradientReport {
  int iterations = 0;
  double relative_residual = 0.0;  // of the recursively updated residual, as the solver saw it
  bool converged = true;
};

class DeviceConjugateGradients {
 public:
  // Uploads S and its inverse diagonal in float, allocates the solver's vectors (canary-guarded) and
  // builds conjugate_gradients.cl with build_options. Throws DeviceError when a buffer exceeds the
  // device or the build fails.
  DeviceConjugateGradients(const ComputeContext& compute, const CsrMatrix& system,
                           const std::vector<double>& inverse_diagonal, const ConjugateGradientOptions& options,
                           const std::string& build_options);
  ~DeviceConjugateGradients();
  DeviceConjugateGradients(const DeviceConjugateGradients&) = delete;
  DeviceConjugateGradients& operator=(const DeviceConjugateGradients&) = delete;

  // b: the caller writes the right-hand side here before solve().
  const DeviceBuffer& right_hand_side() const { return b_; }
  // Solves S x = b in place, x's contents the first guess; enqueues only, except the state reads.
  // Throws DeviceError when the solve ends far from convergence (a stall just above the tolerance,
  // float rounding, still gives a usable x).
  const ConjugateGradientReport& solve(const DeviceBuffer& x);
  const ConjugateGradientReport& last_solve() const { return last_solve_; }

  // Names of the solver's buffers whose canary a kernel overwrote.
  std::vector<std::string> damaged_canaries() const;

 private:
  struct Kernels;
  ComputeContext compute_;
  ConjugateGradientOptions options_;
  int n_ = 0;
  std::unique_ptr<Kernels> kernels_;
  std::size_t group_ = 1;        // local size of every per-vertex kernel
  std::size_t final_group_ = 1;  // local size of the one-group reduction passes
  std::size_t group_count_ = 1;  // work-groups of a per-vertex launch (= partials per reduction)
  DeviceBuffer row_start_, column_, value_, inverse_diagonal_;
  DeviceBuffer b_, r_, z_, p_, q_, partials_, state_;  // written by kernels: canary-guarded
  ConjugateGradientReport last_solve_;
};

}  // namespace physarum::opencl
