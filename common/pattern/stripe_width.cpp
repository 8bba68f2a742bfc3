// Stripe width from area and contour length (band model, see the header).
#include "common/pattern/stripe_width.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {

bool is_stripe(const PatternRegion& region, double aspect_ratio) {
  return aspect_ratio > kStripeAspectRatio || region.hole_count() > 0;
}

std::optional<double> stripe_width(const PatternRegion& region) {
  const double A = region.area, P = region.contour_length;
  if (!(P > 0.0) || !(A > 0.0)) return std::nullopt;
  if (region.touches_boundary || region.hole_count() > 0) return 2.0 * A / P;
  // Rounding can put P^2 a hair below 4 pi A for a disk-like region: clamp.
  return (P - std::sqrt(std::max(P * P - 4.0 * M_PI * A, 0.0))) / M_PI;
}

}  // namespace physarum
