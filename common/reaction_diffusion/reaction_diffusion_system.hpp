#pragma once
// A reaction–diffusion system made ready for one surface: the contract between common/ (which builds
// it from a scene: named model or custom formulas, coefficient maps, diffusion rates and anisotropy,
// initial state, Dirichlet regions) and the two backends that advance it (the reference on the host,
// the OpenCL backend on a device), as SurfaceDomain is for the agent model. Everything here is per
// intrinsic vertex, in SI units; nothing in a backend re-derives it from the scene.
//
// The equations, for morphogen m (0 .. n-1) at intrinsic vertex i, in the lumped finite-element form
// both backends discretise:
//
//   mass_i d(u_m)_i/dt = -(K_m u_m)_i + mass_i R_m(u_0..u_{n-1}, c_0..c_{k-1})_i
//
// K_m is the morphogen's stiffness matrix: the cotan Laplacian with each face's contribution
// weighted by the morphogen's diffusion tensor on that face (isotropic: its rate; anisotropic: rates
// along and across a direction map), so it is symmetric positive semi-definite with zero row sums
// and has the sparsity pattern of SurfaceDomain::laplacian. R_m is the reaction term, a formula in
// the morphogen and coefficient names. Vertices with `fixed` set keep their value (a Dirichlet
// region); everywhere else the boundary is no-flux (the natural condition of the FE form).
#include "common/numerics/csr_matrix.hpp"
#include "common/numerics/time_integrator.hpp"
#include "common/base/element_data.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace physarum {


// The most morphogens a system has: both backends take any count up to it (the OpenCL step sums them
// as one vector of at most eight lanes); Meinhardt's stripe system (004, appendix 8.3) has five.
inline constexpr int kMaxMorphogens = 8;

struct ReactionDiffusionSystem {
  // ---- the kinetics ----
  // The morphogen names (2 to kMaxMorphogens), in layer order: field layer m is morphogen m.
  std::vector<std::string> morphogens;
  // One formula per morphogen: R_m in muparser syntax, over the morphogen names and the coefficient
  // names (numbers; + - * / ^; unary minus; parentheses; the functions exp, log (natural), sqrt, abs,
  // min, max, sin, cos, tanh). A named model ("gray-scott", ...) is given here by its formulas too,
  // so both backends evaluate the one definition.
  std::vector<std::string> reaction;
  // The coefficients the formulas use (F, k, ...), each one value per intrinsic vertex (a number in
  // the scene is a constant array, a map is its values).
  std::vector<std::string> coefficient_names;
  std::vector<IntrinsicVertexData<double>> coefficients;

  // ---- the transport ----
  std::vector<CsrMatrix> stiffness;   // K_m, one per morphogen, pattern of SurfaceDomain::laplacian
  IntrinsicVertexData<double> mass;   // lumped mass per vertex (SurfaceDomain::vertex_mass)

  // ---- state and boundary ----
  std::vector<IntrinsicVertexData<double>> initial;  // the starting value of every morphogen
  // 1 where every morphogen is held at its current value (a Dirichlet region: the values there are
  // those of `initial`, or of the previous layer of a cascaded pattern); 0 elsewhere. Empty: none.
  std::vector<std::uint8_t> fixed;
  // Per morphogen, a floor: after every sub-step (explicit) or step (IMEX) a free vertex's value
  // below it is raised to it. Turk's Turing model needs v >= 0 (a concentration; his own
  // implementation clamps it), without which a grown pattern's troughs run away to -infinity.
  // -infinity: no floor. Empty: none for any morphogen.
  std::vector<double> minimum;

  // ---- time ----
  Integrator integrator = Integrator::Forward;  // Forward or Imex (common/numerics/time_integrator.hpp)
  double time_step = 0.0;  // s per step() of a backend
  // Explicit only: the step is taken as `substeps` equal forward-Euler sub-steps, chosen so that
  // time_step / substeps is below the stability limit of the fastest-diffusing morphogen. 1 for IMEX.
  int substeps = 1;
};

// The checks both backends make before they take a system for `vertex_count` vertices: 2 to 8
// morphogens with usable, distinct names (letters, digits, '_'), one formula, stiffness (n x n, the
// pattern of the first, finite), initial state and floor (finite or -infinity) per morphogen,
// finite coefficient arrays and masses > 0 of one value per vertex, a time step > 0, sub-steps >= 1
// and the forward or IMEX integrator. Throws InputError starting with `who` ("reaction-diffusion", "opencl reaction-diffusion").
void check_reaction_diffusion_system(const ReactionDiffusionSystem& system, int vertex_count, const std::string& who);

}  // namespace physarum
