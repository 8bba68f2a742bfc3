#pragma once
// What a verdict needs beyond the sequential test (api/compare/comparison.cpp), so that `physarum
// compare` never calls two patterns equivalent without having looked at them:
//  * Unrepresented scales. Between two triangulations, a pattern-scale metric measured on the common
//    sampling at a scale the coarser arm's triangles cannot carry (kRepresentableScaleInEdges,
//    common/harness/comparison_metrics.hpp) is Different, with that reason, as soon as the finer arm
//    shows power there (kPatternPowerFloor): the coarser arm cannot have that pattern.
//  * The pattern examined. A comparison none of whose metrics sees the pattern's scales at a scale
//    both arms resolve (every detail energy and band left out, see the verdict's left_out, or only
//    difference-only ones) is Inconclusive, never Equivalent: mean and coverage alone are kept by a
//    blurred pattern.
#include "api/compare/comparison_arms.hpp"

#include <string>
#include <vector>

namespace physarum {

struct UnrepresentedScale {
  size_t metric = 0;         // index in the arms' metric set
  int coarser_arm = 0;       // 0 or 1
  double coarser_edge = 0.0; // its mean edge length (m)
  double finer_power = 0.0;  // the finer arm's mean of the metric over its seeds so far
  bool decides = false;      // finer_power >= kPatternPowerFloor: the metric is Different
  std::string reason;        // one sentence, for the verdict
};

// The sampled metrics of two arms on different triangulations whose scale the coarser arm cannot
// represent (none for arms on one triangulation).
std::vector<UnrepresentedScale> unrepresented_scales(const std::vector<Arm>& arms);

// Judges them on the seeds so far (rows of arm 0 and arm 1: [seed][metric]); true when one decides.
bool judge_unrepresented(std::vector<UnrepresentedScale>& scales, const std::vector<Arm>& arms,
                         const std::vector<std::vector<double>>& arm0, const std::vector<std::vector<double>>& arm1);

// True when some metric of the set sees the pattern's scales at a scale both arms resolve (one that
// an Equivalent verdict can rest on: not difference-only).
bool examines_pattern(const std::vector<MetricInfo>& metrics);

// The metrics' difference_only flags, for SequentialEquivalence::set_difference_only.
std::vector<bool> difference_only_mask(const std::vector<MetricInfo>& metrics);

}  // namespace physarum
