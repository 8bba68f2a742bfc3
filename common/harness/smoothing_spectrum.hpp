#pragma once
// How a field's variation is spread over length scales, measured with the surface's own diffusion
// and no eigenbasis: for a scale s the smoother G_s = (M + t L)^-1 M, t = (s / 2 pi)^2, damps a
// wave of wavelength l by 1 / (1 + (s / l)^2), so
//   detail energy at s   |u - G_s u|^2_M                 the variation finer than about s
//   band power (a, b)    |G_a u - G_b u|^2_M, a < b       the variation between a and b
// both over a normaliser the caller chooses (area x mean^2 for the agent model's energies, area x
// variance for reaction-diffusion's shares of the variance). Any triangulation of a surface, or any set of points on it
// with its own Laplacian, gives them, so two arms on different triangulations carried to one set of
// points (common/harness/common_sampling.hpp) are measured by the same operator.
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <memory>
#include <vector>

namespace physarum {

class SmoothingSpectrum {
 public:
  // Factorises M + t L once per scale (metres, increasing). InputError when a factorisation fails.
  SmoothingSpectrum(const SurfaceDomain& domain, std::vector<double> scales);

  const std::vector<double>& scales() const { return scales_; }

  struct Powers {
    std::vector<double> detail;  // one per scale
    std::vector<double> band;    // between consecutive scales: scales().size() - 1
  };
  // The powers of `u` (one value per domain vertex) over `normaliser`; all 0 when it is not > 0.
  Powers of(const Eigen::VectorXd& u, double normaliser) const;

 private:
  const SurfaceDomain& domain_;
  std::vector<double> scales_;
  std::vector<std::shared_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>> smoothers_;
};

}  // namespace physarum
