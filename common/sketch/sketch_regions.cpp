#include "common/sketch/sketch_regions.hpp"

#include "common/base/errors.hpp"
#include "common/sketch/median.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <tuple>

namespace physarum {

double axial_mean_degrees(const std::vector<double>& degrees) {
  std::complex<double> sum(0.0, 0.0);
  for (const double d : degrees) sum += std::polar(1.0, 2.0 * d * M_PI / 180.0);
  double mean = std::arg(sum) * 90.0 / M_PI;
  return mean < 0.0 ? mean + 180.0 : mean;
}

int SketchRegions::region_of(const Eigen::Vector2d& p) const {
  auto cell = [&](double x, double extent) { return std::clamp(static_cast<int>(std::floor(x / extent * n)), 0, n - 1); };
  return cell(p.y(), window.y()) * n + cell(p.x(), window.x());
}

double SketchRegions::blend(const std::vector<double>& per_region, const Eigen::Vector2d& p, int point_chart) const {
  // Continuous cell coordinates whose integers are the regions' centres.
  auto axis = [&](double x, double extent, int& i0, double& t) {
    const double u = std::clamp(x / extent * n - 0.5, 0.0, static_cast<double>(n - 1));
    i0 = std::min(static_cast<int>(std::floor(u)), std::max(n - 2, 0));
    t = n > 1 ? u - i0 : 0.0;
  };
  int c0 = 0, r0 = 0;
  double tx = 0.0, ty = 0.0;
  axis(p.x(), window.x(), c0, tx);
  axis(p.y(), window.y(), r0, ty);
  const int c1 = std::min(c0 + 1, n - 1), r1 = std::min(r0 + 1, n - 1);
  auto at = [&](int r, int c) { return per_region[static_cast<size_t>(r * n + c)]; };
  const double plain = (1 - ty) * ((1 - tx) * at(r0, c0) + tx * at(r0, c1)) + ty * ((1 - tx) * at(r1, c0) + tx * at(r1, c1));
  if (point_chart < 0 || chart.empty()) return plain;
  double sum = 0.0, weights = 0.0;
  for (const auto& [r, c, w] : {std::tuple{r0, c0, (1 - ty) * (1 - tx)}, std::tuple{r0, c1, (1 - ty) * tx},
                                std::tuple{r1, c0, ty * (1 - tx)}, std::tuple{r1, c1, ty * tx}}) {
    if (chart[static_cast<size_t>(r * n + c)] != point_chart) continue;
    sum += w * at(r, c), weights += w;
  }
  return weights > 0.0 ? sum / weights : plain;
}

namespace {

// n x n regions over the window, their centres set, nothing measured yet.
SketchRegions empty_regions(const Sketch& sketch, int n) {
  SketchRegions result;
  result.n = n;
  result.window = sketch.window;
  result.regions.resize(static_cast<size_t>(n * n));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      result.regions[static_cast<size_t>(r * n + c)].center = {(c + 0.5) * sketch.window.x() / n,
                                                              (r + 0.5) * sketch.window.y() / n};
  return result;
}

// Regions without marks take every attribute of the nearest region with some (by centre distance;
// ties to the first), keeping their own centre and counts.
template <class HasMarks>
void fill_empty_regions(SketchRegions& result, HasMarks has_marks) {
  for (size_t i = 0; i < result.regions.size(); ++i) {
    RegionAttributes& region = result.regions[i];
    if (has_marks(region)) continue;
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < result.regions.size(); ++j) {
      const double d = (result.regions[j].center - region.center).squaredNorm();
      if (has_marks(result.regions[j]) && d < best) best = d, region.filled_from = static_cast<int>(j);
    }
    const RegionAttributes& source = result.regions[static_cast<size_t>(region.filled_from)];
    region.area = source.area, region.aspect = source.aspect, region.orientation = source.orientation;
    region.spacing = source.spacing, region.width = source.width;
  }
}

}  // namespace

SketchRegions sketch_regions(const Sketch& sketch, const SketchAttributes& attributes, int n) {
  if (n < 1) throw InputError(sketch.source + ": " + std::to_string(n) + " regions per side; at least 1");
  if (attributes.spots.empty()) throw InputError(sketch.source + ": the sketch has no spot to take sizes from");
  SketchRegions result = empty_regions(sketch, n);
  std::vector<std::vector<const SpotAttributes*>> members(result.regions.size());
  std::vector<int> region_of_spot;
  for (const SpotAttributes& s : attributes.spots) {
    region_of_spot.push_back(result.region_of(s.center));
    members[static_cast<size_t>(region_of_spot.back())].push_back(&s);
  }
  // A region's spacing: its Delaunay edges with both ends inside it. A spot on a cluster's rim also
  // has edges to the next region's spots, however far, which say nothing of this region's spacing.
  std::vector<std::vector<double>> edges(result.regions.size());
  for (size_t a = 0; a < attributes.spots.size(); ++a)
    for (const int b : attributes.spots[a].neighbours)
      if (static_cast<size_t>(b) > a && region_of_spot[a] == region_of_spot[static_cast<size_t>(b)])
        edges[static_cast<size_t>(region_of_spot[a])].push_back(
            (attributes.spots[a].center - attributes.spots[static_cast<size_t>(b)].center).norm());
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      RegionAttributes& region = result.regions[static_cast<size_t>(r * n + c)];
      const auto& in = members[static_cast<size_t>(r * n + c)];
      region.spots = static_cast<int>(in.size());
      std::vector<double> area, aspect, orientation;
      for (const SpotAttributes* s : in)
        area.push_back(s->area), aspect.push_back(s->aspect), orientation.push_back(s->orientation);
      region.area = median(area), region.aspect = median(aspect);
      region.spacing = median(edges[static_cast<size_t>(r * n + c)]);
      region.orientation = axial_mean_degrees(orientation);
    }
  fill_empty_regions(result, [](const RegionAttributes& r) { return r.spots > 0; });
  return result;
}

SketchRegions stroke_regions(const Sketch& sketch, int n) {
  if (n < 1) throw InputError(sketch.source + ": " + std::to_string(n) + " regions per side; at least 1");
  if (sketch.strokes.empty()) throw InputError(sketch.source + ": the sketch has no stroke to take stripes from");
  SketchRegions result = empty_regions(sketch, n);
  std::vector<std::complex<double>> doubled(result.regions.size());
  std::vector<double> length(result.regions.size()), width(result.regions.size());
  for (const SketchStroke& stroke : sketch.strokes)
    for (size_t k = 0; k + 1 < stroke.points.size(); ++k) {
      const Eigen::Vector2d d = stroke.points[k + 1] - stroke.points[k];
      const size_t r = static_cast<size_t>(result.region_of(0.5 * (stroke.points[k] + stroke.points[k + 1])));
      doubled[r] += std::polar(d.norm(), 2.0 * std::atan2(d.y(), d.x()));
      length[r] += d.norm();
      width[r] += d.norm() * stroke.width_class * kStripeWidthPerClass * sketch.window.x();
      result.regions[r].strokes += 1;
    }
  for (size_t r = 0; r < result.regions.size(); ++r) {
    if (result.regions[r].strokes == 0) continue;
    result.regions[r].orientation = axis_orientation(std::arg(doubled[r]) * 90.0 / M_PI);
    result.regions[r].width = width[r] / length[r];
  }
  fill_empty_regions(result, [](const RegionAttributes& r) { return r.strokes > 0; });
  return result;
}

SketchRegions surface_regions(std::shared_ptr<const SurfaceMarks> marks) {
  SketchRegions result;
  result.n = 0;
  for (size_t k = 0; k < marks->size(); ++k) {
    RegionAttributes r;
    r.spots = 1;
    r.area = marks->area[k];
    r.aspect = marks->aspect[k];
    r.spacing = marks->spacing[k];
    result.regions.push_back(r);
  }
  result.marks = std::move(marks);
  return result;
}

}  // namespace physarum
