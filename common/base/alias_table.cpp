#include "common/base/alias_table.hpp"

#include "common/base/errors.hpp"

#include <cmath>
#include <string>

namespace physarum {

AliasTable AliasTable::build(const std::vector<double>& weights) {
  const int n = static_cast<int>(weights.size());
  if (n == 0) throw InputError("alias table: no weights given");
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double w = weights[i];
    if (!std::isfinite(w) || w < 0.0)
      throw InputError("alias table: weight " + std::to_string(i) + " is " + std::to_string(w) +
                       " (weights must be finite and >= 0)");
    sum += w;
  }
  if (!(sum > 0.0) || !std::isfinite(sum))
    throw InputError("alias table: the weights sum to " + std::to_string(sum) + " (must be positive and finite)");

  // Vose's method: scale weights so the mean is 1, then pair each under-full bucket with an
  // over-full one, which donates exactly the missing mass. Both work lists are stacks of indices.
  AliasTable table;
  table.probability.assign(n, 1.0);
  table.alias.resize(n);
  for (int i = 0; i < n; ++i) table.alias[i] = i;
  std::vector<double> scaled(n);
  std::vector<int> small, large;
  small.reserve(n);
  large.reserve(n);
  for (int i = 0; i < n; ++i) {
    scaled[i] = weights[i] * (static_cast<double>(n) / sum);
    (scaled[i] < 1.0 ? small : large).push_back(i);
  }
  while (!small.empty() && !large.empty()) {
    const int s = small.back(), l = large.back();
    small.pop_back();
    table.probability[s] = scaled[s];
    table.alias[s] = l;
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // Whatever is left is full up to rounding error: it always accepts itself. A zero-weight entry
  // can only end here through rounding when every other bucket was exhausted, which cannot happen
  // while any positive weight remains in `large`; guard anyway so it is never sampled.
  for (int i : large) table.probability[i] = 1.0;
  for (int i : small) table.probability[i] = weights[i] > 0.0 ? 1.0 : 0.0;
  for (int i : small)
    if (weights[i] == 0.0) {
      // Point its alias at any positive-weight entry.
      for (int j = 0; j < n; ++j)
        if (weights[j] > 0.0) {
          table.alias[i] = j;
          break;
        }
    }
  return table;
}

int AliasTable::sample(double u1, double u2) const {
  const int n = size();
  int bucket = static_cast<int>(u1 * n);
  if (bucket >= n) bucket = n - 1;  // u1 rounded up to 1 by a float conversion upstream
  if (bucket < 0) bucket = 0;
  return u2 < probability[bucket] ? bucket : alias[bucket];
}

}  // namespace physarum
