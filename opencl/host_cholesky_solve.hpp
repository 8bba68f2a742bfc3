#pragma once
// A backward-Euler / IMEX system S x = b of a device field (common/model/pheromone_operators.hpp,
// opencl/reaction_diffusion.hpp) solved on the host by a sparse Cholesky factorization computed
// once, instead of conjugate gradients on the device. Where the OpenCL device is the host's own CPU
// (PoCL) the device's memory is the host's: the field is mapped in place (opencl/runtime/mapped_buffer.hpp),
// and one pair of triangular solves replaces the dozens of CG iterations whose launches and
// reductions dominate a field's step. Both device field models use this one class: the pheromone
// and every morphogen of the reaction-diffusion IMEX step.
//
// The pheromone's factor is single precision, like the device field it serves: a float field cannot
// hold a double solution, and the float factor's triangular solves move half the value bytes of the
// reference's double ones. S is symmetric positive definite and well conditioned for the step sizes
// the field uses; the factor is computed in double and rounded once, so a solve keeps about 1e-6
// relative accuracy, the CG's own tolerance, and the pheromone's decay forgets old errors. The
// reaction-diffusion IMEX factors stay double: there the errors of hundreds of steps add up through
// kinetics that keep them (a float factor left the backends 5e-4 apart after 200 Gray-Scott steps,
// test_reaction_diffusion_backends; double keeps them within 1e-4).
//
// The triangular solves are our own rather than Eigen's: Eigen's forward sweep runs down L's
// columns and subtracts each from the rows below (a read-modify-write of the solution per entry),
// ours runs along L's rows as dot products, with L kept a second time by rows for it while both
// copies fit in the cache (kMaxRowCopyBytes); both sweeps read each entry's index and value side by
// side and keep four independent sums, and 1/D is folded into the backward sweep. On systems of
// 1k-3k vertices that is ~1.6x faster than Eigen's solve in float or double (bench/README.md, "The
// implicit solve"), which is what puts the device's implicit step ahead of the reference's at small
// sizes, where the solve is the whole step.
//
// Past kMinSupernodalRows the factor is CHOLMOD's supernodal L L^T instead (METIS nested dissection),
// rounded to the field's precision and solved by common/numerics/supernodal_solve.hpp: dense column blocks
// carry one row index per block row rather than one per entry, so a float entry costs 4 bytes
// instead of 8, and the elimination tree's subtrees are solved on both cores. At 10^5-10^6
// vertices that solve is 3-4x faster than the simplicial one, which was bound by L's bytes and
// by one core; below ~12k vertices its blocks' padding and per-supernode cost made it slower.
//
// Where it solves is the caller's choice (implicit_solve_on_host below): the class itself only
// works on host memory, so it serves any device.
#include "common/numerics/csr_matrix.hpp"
#include "opencl/runtime/device_selection.hpp"

#include <cstddef>
#include <memory>
#include <string>

namespace physarum::opencl {

enum class FactorPrecision { Single, Double };

// Up to this many bytes of L's entries (both copies) the forward sweep runs along a copy of L by
// rows. Past it the second copy would push the first out of the cache, so L is kept once, by
// columns (measured on perturbed grids here, 32 MB of L3: at 32k vertices, 13 MB for both copies,
// the two forward sweeps tied; at 57k, 28 MB, the row sweep over two copies took twice as long).
inline constexpr std::size_t kMaxRowCopyBytes = std::size_t{8} << 20;

// Systems of at least this many rows are factored supernodally instead (measured on spot's pheromone
// system in float, `BM_HostCholeskySolve`: simplicial / supernodal 0.046 / 0.073 ms at 3.0k rows,
// 0.31 / 0.32 at 12k, 0.96 / 0.79 at 26k, 2.9 / 1.2 at 54k, 8.9 / 2.9 at 106k).
inline constexpr int kMinSupernodalRows = 20000;

class HostCholeskySolve {
 public:
  // Factors S (symmetric positive definite, both triangles stored) as P S P^T = L D L^T (Eigen's
  // simplicial factorization in double, fill-reducing AMD ordering P), then keeps L and 1/D at
  // `precision` (not L L^T: its solves divide by L's diagonal in both sweeps, where L D L^T's unit
  // L multiplies once by 1/D). Throws InputError naming `what` when it is not positive definite at
  // that precision (a pivot <= 0).
  // Systems of at least `min_supernodal_rows` rows get the supernodal factor (CHOLMOD's analysis and
  // factorization, in double) instead. Both last arguments are for tests and benchmarks (each
  // layout on one system).
  HostCholeskySolve(const CsrMatrix& system, FactorPrecision precision, const std::string& what,
                    std::size_t max_row_copy_bytes = kMaxRowCopyBytes, int min_supernodal_rows = kMinSupernodalRows);
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
