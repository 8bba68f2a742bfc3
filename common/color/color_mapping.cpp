#include "common/color/color_mapping.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {

std::string RemapCurve::points_problem(const std::vector<std::pair<double, double>>& points) {
  if (points.size() < 2) return "needs at least 2 points, has " + std::to_string(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const auto [x, y] = points[i];
    const std::string which = "point " + std::to_string(i);
    if (!std::isfinite(x) || x < 0.0 || x > 1.0) return which + ": x = " + std::to_string(x) + " is outside [0, 1]";
    if (!std::isfinite(y) || y < 0.0 || y > 1.0) return which + ": y = " + std::to_string(y) + " is outside [0, 1]";
    if (i > 0 && !(x > points[i - 1].first))
      return which + ": x = " + std::to_string(x) + " does not exceed the previous point's " +
             std::to_string(points[i - 1].first) + " (x must increase strictly)";
  }
  return {};
}

RemapCurve::RemapCurve(std::vector<std::pair<double, double>> points, const std::string& where)
    : points_(std::move(points)) {
  if (const std::string problem = points_problem(points_); !problem.empty()) throw InputError(where + ": " + problem);
}

double RemapCurve::operator()(double t) const {
  if (points_.empty()) return t;
  if (t <= points_.front().first) return points_.front().second;
  if (t >= points_.back().first) return points_.back().second;
  const auto upper = std::upper_bound(points_.begin(), points_.end(), t,
                                      [](double value, const std::pair<double, double>& p) { return value < p.first; });
  const auto& [x0, y0] = *(upper - 1);
  const auto& [x1, y1] = *upper;
  return y0 + (y1 - y0) * (t - x0) / (x1 - x0);
}

double ColorMapping::upper(const InputVertexData<double>& values) const {
  if (high) return *high;
  double top = -std::numeric_limits<double>::infinity();
  for (double v : values)
    if (std::isfinite(v)) top = std::max(top, v);
  return top;
}

double ColorMapping::normalise(double value, double upper_end) const {
  double t = 0.0;
  // NaN values and an empty range stay at t = 0 (before gamma and remap, so a remap can still
  // give them a colour of its choosing).
  if (upper_end > low && !std::isnan(value)) t = std::clamp((value - low) / (upper_end - low), 0.0, 1.0);
  if (gamma != 1.0) t = std::pow(t, gamma);
  return std::clamp(remap(t), 0.0, 1.0);
}

SrgbColor ColorMapping::color_float(double value, double upper_end) const {
  return map.sample(normalise(value, upper_end));
}

Rgb8 ColorMapping::color(double value, double upper_end) const { return map.sample8(normalise(value, upper_end)); }

}  // namespace physarum
