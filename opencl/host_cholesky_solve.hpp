#pragma once
// A backward-Euler / IMEX system S x = b of a device field (common/pheromone_operators.hpp,
// opencl/reaction_diffusion.hpp) solved on the host by a sparse Cholesky factorization computed
// once, instead of conjugate gradients on the device. Where the OpenCL device is the host's own CPU
// (PoCL) the device's memory is the host's: the field is mapped in place (opencl/mapped_buffer.hpp),
// and one pair of triangular solves replaces the dozens of CG iterations whose launches and
// reductions dominate a field's step. Both device field models use this one class: the pheromone
// and every morphogen of the reaction-diffusion IMEX step.
//
// The pheromone's factor is single precision, like the device field it serves: a float field cannot
// hold a double solution, and the float factor's triangular solves move half the bytes of the
// reference's double ones (the solve is memory-bound). S is symmetric positive definite and well
// conditioned for the step sizes the field uses, so a float factorization keeps about 1e-6 relative
// accuracy per solve, the CG's own tolerance, and the pheromone's decay forgets old errors. The
// reaction-diffusion IMEX factors are double: there the errors of hundreds of steps add up through
// kinetics that keep them (a float factor left the backends 5e-4 apart after 200 Gray-Scott steps,
// test_reaction_diffusion_backends; double keeps them within 1e-4).
//
// Where it solves is the caller's choice (implicit_solve_on_host below): the class itself only
// works on host memory, so it serves any device.
#include "common/csr_matrix.hpp"
#include "opencl/device_selection.hpp"

#include <memory>
#include <string>

namespace physarum::opencl {

enum class FactorPrecision { Single, Double };

class HostCholeskySolve {
 public:
  // Factors S (symmetric positive definite, both triangles stored) as L D L^T in float or double
  // (not L L^T: its solves divide by L's diagonal in both sweeps, one scalar division per row and
  // sweep, where L D L^T's unit L divides once, by D, vectorised: 7 % of a 3k-vertex step, enough
  // to put the device's step behind the reference's). Throws InputError naming `what` when it is
  // not positive definite at that precision (a pivot <= 0).
  HostCholeskySolve(const CsrMatrix& system, FactorPrecision precision, const std::string& what);
  ~HostCholeskySolve();
  HostCholeskySolve(const HostCholeskySolve&) = delete;
  HostCholeskySolve& operator=(const HostCholeskySolve&) = delete;

  int size() const { return n_; }
  // x = S^-1 b for size() floats each; b and x may be the same array. Allocates nothing.
  void solve(const float* b, float* x);

 private:
  struct Factor;
  int n_ = 0;
  std::unique_ptr<Factor> factor_;
};

// Whether the automatic choice solves an implicit system of `vertex_count` unknowns with the host
// factorization rather than device conjugate gradients (DeviceTuning::host_implicit_solve_max_vertices:
// every size on a CPU device; on a GPU only systems so small that CG's fixed cost of launches beats
// the copies and the host's triangular solves).
bool implicit_solve_on_host(const DeviceInfo& device, int vertex_count);

}  // namespace physarum::opencl
