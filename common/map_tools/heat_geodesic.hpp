#pragma once
// Geodesic distance by the heat method (Crane, Weischedel & Wardetzky, "Geodesics in Heat", 2013) on
// the intrinsic triangulation of a SurfaceDomain:
//   1. heat flow for a short time t = m h^2 (h the mean intrinsic edge length, m the time factor):
//      (M + t L) u = delta_seeds, one backward Euler step from the seeds' indicator;
//   2. the unit field X = -grad u / |grad u| on every face (heat flows away from the seeds), except on
//      the faces with exactly one seed corner, where X is the gradient of the distance's own
//      interpolant (0 at the seed, the edge lengths beside it), and those with three (inside a region
//      of seeds), where X = 0 (heat_geodesic.cpp says why);
//   3. the distance phi solves the Poisson problem L phi = -div X, fixed per connected piece so that
//      its smallest value over the seeds is 0 (values below 0 next to the seeds are clamped to 0).
// L is the PSD cotan Laplacian and M the lumped mass of the domain. On a surface with boundary, step 1
// is the average of the Neumann solution (the system above) and the Dirichlet one (u = 0 on every
// boundary vertex), as the authors recommend: Neumann alone bends the level sets to meet the boundary
// at right angles, Dirichlet alone makes them follow it. A seed ON the boundary heats the Dirichlet
// solution at its Neumann value; with seeds on the boundary alone there is no Dirichlet solution (it
// would hold them at 0), the result is Neumann's, and the faces at the boundary where the geodesics
// leave the surface take their direction from the interior (common/map_tools/boundary_outflow.hpp).
//
// Far from the seeds the heat falls below what one solve resolves (about e^-1 per edge: 440 decades
// ~1000 edges away), so step 1 is solved in levels, each rescaled from the band where the last one
// stopped (heat_geodesic.cpp); a surface less than ~1000 edges across needs one level.
//
// The factorizations (supernodal Cholesky through CHOLMOD, one METIS analysis shared by all three:
// common/numerics/shared_cholesky.hpp) are built once, in the constructor, for one domain and one t; every
// distance() after that costs one pair of triangular solves per heat level (twice with a boundary)
// plus one for the Poisson step, and two passes over the faces. The triangular solves are ours, not
// CHOLMOD's: on large factors they run by subtrees of the elimination tree on all cores
// (common/numerics/supernodal_solve.hpp; at 1.31 M faces 59 ms against CHOLMOD's serial 98 ms on this 2-core
// machine when the second core is free, about even when it is not), with the same result bits on
// any number of threads. The domain must outlive the solver.
#include "common/base/element_data.hpp"
#include "common/surface/surface_domain.hpp"

#include <memory>
#include <vector>

namespace physarum {

class HeatGeodesicSolver {
 public:
  // Factors M + tL (and its Dirichlet restriction when the surface has a boundary) and L with one
  // vertex pinned per connected piece. time_factor (m) must be > 0 (std::invalid_argument otherwise;
  // scenes check it first). InputError when a factorization fails (a domain with degenerate faces).
  // `ordering`, when given, is the Laplacian's fill-reducing order (common/map_tools/surface_solvers.hpp),
  // used instead of running METIS here.
  explicit HeatGeodesicSolver(const SurfaceDomain& domain, double time_factor = 1.0, const std::vector<int>* ordering = nullptr);
  ~HeatGeodesicSolver();
  HeatGeodesicSolver(const HeatGeodesicSolver&) = delete;
  HeatGeodesicSolver& operator=(const HeatGeodesicSolver&) = delete;

  // Distance from the nearest of `seeds` (intrinsic vertex ids) at every intrinsic vertex.
  // InputError when `seeds` is empty, names a vertex out of range, or misses a connected piece.
  IntrinsicVertexData<double> distance(const std::vector<int>& seeds) const;

  double mean_edge_length() const { return mean_edge_length_; }
  double time() const { return time_; }  // t = m h^2
  bool has_boundary() const;

 private:
  struct Factorizations;
  const SurfaceDomain& domain_;
  double mean_edge_length_ = 0.0, time_ = 0.0;
  std::unique_ptr<Factorizations> factors_;
};

// The mean length of the domain's edges (each interior edge counted once), from its face layouts
// (not comparison_metrics' mean_edge_length, the side of an equilateral triangle of mean area).
double mean_intrinsic_edge_length(const SurfaceDomain& domain);

}  // namespace physarum
