#pragma once
// The width of a stripe (an elongated segmented region, common/pattern/pattern_segmentation.hpp), from its
// area A and the length P of its contour (the iso-line; the mesh boundary does not count), with the
// model of a stripe as a band of constant width w around a centre line of length L:
//   * a band with no free ends — it runs to the mesh boundary at both ends, or closes on itself (a
//     ring, so the region has a hole) — has A = w L and P = 2 L, so w = 2 A / P, exactly;
//   * a band with two free, rounded ends (the set of points within w/2 of a curve of length L: a
//     stadium when the curve is straight) has A = w L + pi w^2 / 4 and P = 2 L + pi w; eliminating L,
//     pi w^2 / 4 - (P / 2) w + A = 0, so w = (P - sqrt(P^2 - 4 pi A)) / pi (the smaller root; real
//     by the isoperimetric inequality, and 2 r for a disk of radius r, its diameter).
// A region that reaches the boundary or has a hole takes the first rule, an isolated region without
// holes the second. A band that reaches the boundary at one end only comes out about w (pi w / 8L)
// too narrow by the first rule.
#include "common/pattern/pattern_segmentation.hpp"

#include <optional>

namespace physarum {

// The aspect ratio (common/pattern/spot_shape.hpp) above which a region counts as a stripe; a region with a
// hole is one whatever its aspect.
inline constexpr double kStripeAspectRatio = 3.0;

bool is_stripe(const PatternRegion& region, double aspect_ratio);

// The width by the rules above; nothing when the region has no contour (it covers its whole surface).
std::optional<double> stripe_width(const PatternRegion& region);

}  // namespace physarum
