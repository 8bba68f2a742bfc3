#include "common/harness/harmonic_bands.hpp"

#include <algorithm>

namespace physarum {

HarmonicBandAssignment assign_harmonic_bands(const Eigen::VectorXd& lambda, double lambda_pattern, int max_bands) {
  HarmonicBandAssignment a;
  const int computed = static_cast<int>(lambda.size());
  const double lambda_max = computed > 0 ? lambda.maxCoeff() : 0.0;
  // Eigenvalues this close are one eigenspace (the solver's relative accuracy is far better).
  const double tie = 1e-6 * lambda_max;
  int first = 0, end = computed;
  while (first < computed && (lambda[first] <= 1e-8 * lambda_max || lambda[first] < lambda_pattern)) ++first;
  while (first > 0 && first < computed && lambda[first] - lambda[first - 1] <= tie) ++first;  // whole eigenspaces
  while (end > first && lambda[computed - 1] - lambda[end - 1] <= tie) --end;
  a.usable = end - first;
  a.bands = std::max(0, std::min<int>(max_bands, a.usable / kMinModesPerBand));
  a.band_of_mode.assign(static_cast<size_t>(computed), -1);
  if (a.bands < 1) return a;
  int band = 0;
  for (int k = first; k < end; ++k) {
    const bool cluster_starts = k == first || lambda[k] - lambda[k - 1] > tie;
    while (cluster_starts && band + 1 < a.bands && (k - first) >= (band + 1) * a.usable / a.bands) ++band;
    a.band_of_mode[static_cast<size_t>(k)] = band;
  }
  return a;
}

}  // namespace physarum
