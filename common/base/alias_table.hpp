#pragma once
// Vose's alias method: O(1) sampling of an index with probability proportional to its weight.
#include <cstdint>
#include <vector>

namespace physarum {

struct AliasTable {
  std::vector<double> probability;  // acceptance probability of bucket i
  std::vector<int> alias;           // index taken when bucket i rejects

  // Weights must be finite and >= 0 with a positive sum (InputError otherwise).
  static AliasTable build(const std::vector<double>& weights);
  int size() const { return static_cast<int>(probability.size()); }
  // u1, u2 uniform in [0, 1): the first picks a bucket, the second accepts it or takes its alias.
  int sample(double u1, double u2) const;
};

}  // namespace physarum
