#pragma once
// From a reaction–diffusion scene (common/scene/scene_reaction_diffusion.hpp), its surface and its
// evaluated maps to the ReactionDiffusionSystem both backends advance (common/reaction_diffusion/reaction_diffusion_system.hpp):
//
//   coefficients   per vertex: a number everywhere, or a map's values;
//   stiffness K_m  sum over faces f of A_f grad(phi_i)^T D_f grad(phi_j), the linear finite-element
//                  form of -div(D grad u) (the same assembly as SurfaceDomain::laplacian, whose
//                  pattern it shares). D_f = a_f I isotropic, a_f the mean of the face's three vertex
//                  rates (so a constant rate gives exactly rate x laplacian); anisotropic D_f =
//                  a_f d d^T + b_f (I - d d^T) with d the face's unit direction from the vector map
//                  and b_f = ratio x a_f (a face whose direction is zero diffuses isotropically);
//   initial        uniform -> seed region blend -> spots -> noise -> Dirichlet values (below);
//   fixed          1 where the "dirichlet" map is >= 0.5;
//   substeps       explicit only: the smallest n with time_step / n <= kExplicitSafety x dt_max,
//                  dt_max = 2 / max_m lambda_max(M^-1 K_m), the forward-Euler limit of the fastest
//                  diffusing morphogen (lambda_max by Lanczos on the symmetric M^-1/2 K M^-1/2).
//
// The initial state is deterministic in the scene's seed: the spot centres are drawn by vertex mass
// (an area-uniform choice of vertex) from Philox streams keyed (seed, spot), the noise of vertex i
// and morphogen m is noise x (2 U - 1) with U from the stream (seed, i), block m
// (common/base/random_streams.hpp, purposes ReactionSpot and ReactionNoise).
#include "common/base/element_data.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/surface/surface_domain.hpp"

#include <array>

namespace physarum {

// The fraction of the forward-Euler limit a sub-step may use: below 1 so the reaction term (not in
// the limit) has room, and the fastest diffusion mode is damped rather than merely not growing.
inline constexpr double kExplicitSafety = 0.9;

// Builds the whole system. InputError naming the key, the intrinsic vertex and the value when a map
// gives a negative diffusion rate or a non-finite coefficient.
ReactionDiffusionSystem build_reaction_diffusion_system(const Scene& scene, const PreparedSurface& surface,
                                                        const EvaluatedMaps& maps);

// K for a per-vertex diffusion rate; with `direction` (per face, in the face's frame, any length) the
// rate is the one along it and ratio x rate the one across, the ratio per vertex (`ratio`, > 0; a
// face takes its corners' mean, as it takes the rate's).
CsrMatrix diffusion_stiffness(const SurfaceDomain& domain, const IntrinsicVertexData<double>& rate,
                              const IntrinsicFaceData<std::array<double, 2>>* direction = nullptr,
                              const IntrinsicVertexData<double>* ratio = nullptr);

// lambda_max of M^-1 K (K symmetric positive semi-definite, M the diagonal lumped mass), by Lanczos;
// where that does not converge in 1000 restarts, Gershgorin's upper bound on it (never below it, so
// a step chosen from it is still stable).
double largest_diffusion_eigenvalue(const CsrMatrix& stiffness, const IntrinsicVertexData<double>& mass);

// 2 / max over morphogens of lambda_max(M^-1 K_m): the largest forward-Euler step that keeps pure
// diffusion stable (+infinity when nothing diffuses).
double explicit_stability_limit(const ReactionDiffusionSystem& system);

// The sub-steps an explicit step of `time_step` needs under `stability_limit` (>= 1).
int explicit_substeps(double time_step, double stability_limit);

}  // namespace physarum
