#pragma once
// The backward-Euler system S x = b of a device field (common/pheromone_operators.hpp) solved on the
// host by a sparse Cholesky factorization computed once, instead of conjugate gradients on the
// device. Where the OpenCL device is the host's own CPU (PoCL), the device's memory is the host's:
// reading b and writing x are copies within one RAM, and one pair of triangular solves replaces the
// dozens of CG iterations whose launches and reductions dominate a small field's step. On a GPU the
// copies cross the bus every step, so the device's CG stays the choice there
// (opencl/diffusion_decay.hpp: ImplicitSolver).
//
// The factor is single precision, like the device field it serves: a float field cannot hold a
// double solution, and the float factor's triangular solves move half the bytes of the reference's
// double ones (the solve is memory-bound). S is symmetric positive definite and well conditioned
// for the step sizes the field uses, so float Cholesky keeps about 1e-6 relative accuracy, the CG's
// own tolerance.
#include "common/csr_matrix.hpp"
#include "opencl/compute_context.hpp"
#include "opencl/device_buffer.hpp"

#include <memory>
#include <vector>

namespace physarum::opencl {

class HostCholeskySolve {
 public:
  // Factors S (InputError when it is not positive definite) and allocates b on the device.
  HostCholeskySolve(const ComputeContext& compute, const CsrMatrix& system);
  ~HostCholeskySolve();
  HostCholeskySolve(const HostCholeskySolve&) = delete;
  HostCholeskySolve& operator=(const HostCholeskySolve&) = delete;

  // b: the caller's kernels write the right-hand side here before solve().
  const DeviceBuffer& right_hand_side() const { return b_; }
  // x = S^-1 b: reads b (waiting for the queue), solves on the host, writes x (waiting for the copy).
  void solve(const DeviceBuffer& x);

 private:
  struct Factor;
  ComputeContext compute_;
  int n_ = 0;
  std::unique_ptr<Factor> factor_;
  DeviceBuffer b_;
  std::vector<float> host_;  // b, then x
};

}  // namespace physarum::opencl
