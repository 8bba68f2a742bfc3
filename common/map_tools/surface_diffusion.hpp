#pragma once
// Short-time diffusion of a scalar map on the intrinsic triangulation (paper Sec. 3.3: a seed map
// blurred before it drives a control; the "diffuse" map source of common/maps/map_definition.hpp).
//
// The heat equation du/dt = -M^-1 L u (L the cotan Laplacian, M the lumped mass, diffusivity 1) is
// integrated over `time` with `steps` backward-Euler steps of h = time / steps:
//   (M + h L) u_{k+1} = M u_k.
// Backward Euler because it is unconditionally stable (any time, any mesh, however fine) and
// because its matrix is an M-matrix on a Delaunay triangulation (the intrinsic one is), so the
// step is a weighted average: the maximum never increases and the minimum never decreases. Summing
// the rows (L's columns sum to zero) shows that sum_i m_i u_i is conserved exactly. More steps
// follow the true heat flow more closely; one step is already a smooth, local blur.
//
// Units: the domain's (the scene's metres after scale_to_area), so `time` is in m^2 and the blur's
// standard deviation is about sqrt(2 time) metres on a flat part of the surface.
#include "common/base/element_data.hpp"
#include "common/surface/surface_domain.hpp"

#include "common/numerics/shared_cholesky.hpp"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace physarum {

// The factorized backward-Euler step of one step size, reused for any number of steps and maps.
class BackwardEulerDiffusion {
 public:
  // Factors M + step L once (in `ordering`, the Laplacian's fill-reducing order when the caller
  // has it: common/map_tools/surface_solvers.hpp). InputError when step <= 0 or is not finite, or the
  // factorization fails.
  BackwardEulerDiffusion(const SurfaceDomain& domain, double step, const std::vector<int>* ordering = nullptr);

  // One step: u_{k+1} from u_k (one value per intrinsic vertex).
  IntrinsicVertexData<double> step(const IntrinsicVertexData<double>& u) const;

 private:
  Eigen::VectorXd mass_;
  std::shared_ptr<SharedCholesky> solver_;  // CHOLMOD, supernodal (one factorization)
};

// `u` diffused for `time` in `steps` equal backward-Euler steps. InputError when time <= 0, steps <
// 1, or u has not one value per intrinsic vertex.
IntrinsicVertexData<double> diffuse_on_surface(const SurfaceDomain& domain, const IntrinsicVertexData<double>& u,
                                               double time, int steps = 1, const std::vector<int>* ordering = nullptr);

}  // namespace physarum
