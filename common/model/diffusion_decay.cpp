#include "common/model/diffusion_decay.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {

DepositOrder deposit_order(Integrator integrator) {
  return integrator == Integrator::Forward ? DepositOrder::AfterTransport : DepositOrder::BeforeTransport;
}

double forward_euler_stable_step(const CsrMatrix& L, const IntrinsicVertexData<double>& diffuse_over_mass,
                                 const IntrinsicVertexData<double>& decay_rate) {
  double max_a = 0.0, max_g = 0.0;
  for (int i = 0; i < L.rows; ++i) {
    double diagonal = 0.0, absolute_row = 0.0;
    for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
      if (L.column[k] == i) diagonal += L.value[k];
      absolute_row += std::abs(L.value[k]);
    }
    max_a = std::max(max_a, diffuse_over_mass[i] * diagonal + decay_rate[i]);
    max_g = std::max(max_g, diffuse_over_mass[i] * absolute_row + decay_rate[i]);
  }
  constexpr double kSafety = 0.9;
  const double bound = std::min(max_a > 0 ? 1.0 / max_a : std::numeric_limits<double>::infinity(),
                                max_g > 0 ? 2.0 / max_g : std::numeric_limits<double>::infinity());
  return kSafety * bound;
}

int forward_euler_sub_steps(double time_step, double stable_step) {
  return time_step <= stable_step ? 1 : static_cast<int>(std::ceil(time_step / stable_step));
}

}  // namespace physarum
