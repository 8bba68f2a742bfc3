#pragma once
// A sketch drawn in any paint program (a PNG, or any image OpenImageIO reads): dark marks on a light
// background, read as it is seen. The image spans the window [0, 1] x [0, height/width], its top row
// at the window's largest y.
//
// The rules, in order:
//   - a pixel is part of a mark when its luminance (over white, where the image has alpha) is below
//     0.5; a saturated red pixel (r > 0.5, g and b < 0.35) marks a stroke explicitly;
//   - marks are 8-connected groups of such pixels; background enclosed by a dark mark belongs to it,
//     so an outlined ellipse is a spot like a filled one (its radii are measured to the middle of the
//     drawn line: half the line's width, its area over its length, is taken off);
//   - a mark is measured by its area moments (common/sketch/mark_moments.hpp): an ellipse with the
//     same area covariance;
//   - a red mark is a stroke; a dark mark is a stroke when it is long and thin (minor / major radius
//     < kStrokeAspect) or fills little of its ellipse (area / (pi a b) < kStrokeFill: a bent line),
//     a spot otherwise. A stroke runs through its centroid along its major axis; its width is its
//     area over its length, and its width class the nearest of 1..4 with class k about k% of the
//     window's width.
//
// InputError naming the file: unreadable or empty images, images over the pixel budget
// (common/base/image_budget.hpp, checked from the header), a picture without marks, and marks of
// fewer than kMinMarkPixels pixels (too small to measure; the message gives the smallest size).
#include "common/sketch/sketch.hpp"

#include <string>

namespace physarum {

constexpr double kStrokeAspect = 0.25;
constexpr double kStrokeFill = 0.6;
constexpr int kMinMarkPixels = 20;

Sketch sketch_from_image(const std::string& path);

}  // namespace physarum
