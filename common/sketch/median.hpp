#pragma once
// The median of a list, 0 for an empty one: how the sketch summarises its marks per region, its
// training runs per rate and the grown spots per region (robust to the odd spot the segmentation
// splits or merges).
#include <algorithm>
#include <vector>

namespace physarum {

inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace physarum
