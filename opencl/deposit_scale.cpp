#include "opencl/deposit_scale.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace physarum::opencl {

double fixed_point_scale_for(double largest_total) {
  const int exponent =
      largest_total > 0.0 ? std::min(60, static_cast<int>(std::floor(62.0 - std::log2(largest_total)))) : 40;
  return std::ldexp(1.0, exponent);
}

double fixed_point_deposit_scale(const IntrinsicVertexData<double>& deposit_rate, int agent_count, double time_step) {
  double max_rate = 0.0, min_positive_rate = INFINITY;
  for (double r : deposit_rate) {
    max_rate = std::max(max_rate, r);
    if (r > 0.0) min_positive_rate = std::min(min_positive_rate, r);
  }
  const double worst_step_total = std::max(1, agent_count) * max_rate * time_step;
  const double scale = fixed_point_scale_for(worst_step_total);
  if (std::isfinite(min_positive_rate) && min_positive_rate * time_step * scale < 0x1p20)
    throw InputError("opencl simulation: " + std::to_string(agent_count) + " agents depositing up to " +
                     std::to_string(max_rate) + " per second leave too little fixed-point resolution for the "
                     "smallest deposit rate " + std::to_string(min_positive_rate) +
                     " (64-bit deposits would round at more than 1e-6); reduce the spread of deposit rates");
  return scale;
}

}  // namespace physarum::opencl
