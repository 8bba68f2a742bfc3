#pragma once
// How field values become colours: a colour map and the reparameterisation of Sec. 3.4 / Fig. 14 of
// the paper, applied in this order to a value v:
//   1. levels:  t = (v - low) / (high - low), clamped to [0, 1]      (the input range)
//   2. gamma:   t = t^gamma                                            (gamma > 1 darkens the low end)
//   3. remap:   t = remap(t), a piecewise-linear curve through (x, y) points
//   4. lookup:  colour = map.sample(t)
// The remap curve need not be monotone: [[0,0],[0.5,1],[1,0]] sends both the low and the high end of
// the range to the map's start and the middle to its end, which is how a spot's smooth falloff
// becomes a coloured ring around its peak (the blue-ringed octopus of Fig. 14).
#include "common/color/color_map.hpp"
#include "common/base/element_data.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace physarum {

// A piecewise-linear function [0, 1] -> [0, 1] through points sorted by strictly increasing x;
// left of the first point it is the first y, right of the last the last y. No points: identity.
class RemapCurve {
 public:
  RemapCurve() = default;
  // InputError (prefixed with `where`) when the points are not a valid curve (points_problem).
  explicit RemapCurve(std::vector<std::pair<double, double>> points, const std::string& where = "remap");

  // "" when valid, else what is wrong: at least two points, x strictly increasing, x and y finite
  // and inside [0, 1].
  static std::string points_problem(const std::vector<std::pair<double, double>>& points);

  bool identity() const { return points_.empty(); }
  const std::vector<std::pair<double, double>>& points() const { return points_; }
  double operator()(double t) const;

 private:
  std::vector<std::pair<double, double>> points_;
};

struct ColorMapping {
  ColorMap map = ColorMap::viridis();
  double low = 0.0;
  std::optional<double> high;  // default: the largest value (all `low`-coloured when that is <= low)
  double gamma = 1.0;          // > 0
  RemapCurve remap;            // identity when empty

  // The effective upper end for `values`.
  double upper(const InputVertexData<double>& values) const;
  // The map parameter in [0, 1] for one value, given the effective upper end: levels, gamma and
  // remap applied (steps 1-3 above).
  double normalise(double value, double upper_end) const;
  // The colour of one value: map.sample(normalise(value, upper_end)).
  SrgbColor color_float(double value, double upper_end) const;
  Rgb8 color(double value, double upper_end) const;
};

}  // namespace physarum
