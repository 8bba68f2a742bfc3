#include "common/color/layer_colours.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

// The lowest and highest value of `field` where `share` is 0 (every value when `share` is empty).
std::pair<double, double> value_range(const std::vector<double>& field, const std::vector<double>& share = {}) {
  double low = HUGE_VAL, high = -HUGE_VAL;
  for (size_t v = 0; v < field.size(); ++v)
    if (share.empty() || share[v] == 0.0) low = std::min(low, field[v]), high = std::max(high, field[v]);
  return {low, high};
}

// `set` (its map, gamma and remap; not its levels) spread over [valley, peak].
ColorMapping valley_to_peak(const ColorMapSettings& set, double valley, double peak) {
  if (!std::isfinite(valley) || !std::isfinite(peak))
    throw InputError("colour set " + set.map.name() + ": the field's valley and peak must be finite");
  ColorMapping m;
  m.map = set.map;
  m.gamma = set.gamma;
  m.remap = set.remap;
  m.low = valley;
  // A flat field: every value at the set's first colour.
  m.high = peak > valley ? peak : valley + 1.0;
  return m;
}

}  // namespace

LayerColours::LayerColours(const ColorMapSettings& set, const std::vector<double>& field) {
  if (field.empty()) throw InputError("layer colours: an empty field");
  const auto [low, high] = value_range(field);
  first_ = valley_to_peak(set, low, high);
}

LayerColours::LayerColours(const ColorMapSettings& first_set, const std::vector<double>& first_field,
                           const ColorMapSettings& second_set, const std::vector<double>& final_field,
                           const std::vector<double>& first_share)
    : LayerColours(first_set, first_field) {
  if (final_field.size() != first_field.size() || first_share.size() != first_field.size())
    throw InputError("layer colours: " + std::to_string(first_field.size()) + " first-layer values, " +
                     std::to_string(final_field.size()) + " final values and " + std::to_string(first_share.size()) +
                     " shares (one each per vertex)");
  const auto [low, high] = value_range(final_field, first_share);
  if (low > high) throw InputError("layer colours: the first layer's spots cover every vertex, no second layer shows");
  second_ = valley_to_peak(second_set, low, high);
  layered_ = true;
}

SrgbColor LayerColours::at(double first, double last, double first_share) const {
  const SrgbColor a = first_.color_float(first, *first_.high);
  if (!layered_) return a;
  const SrgbColor b = second_.color_float(last, *second_.high);
  const double w = std::clamp(first_share, 0.0, 1.0);
  return {w * a[0] + (1 - w) * b[0], w * a[1] + (1 - w) * b[1], w * a[2] + (1 - w) * b[2]};
}

}  // namespace physarum
