// Pattern analysis: segmentation, per-region measures, spacing, and their JSON summary.
#include "common/pattern/pattern_analysis.hpp"

#include "common/base/errors.hpp"
#include "common/pattern/pattern_segmentation.hpp"
#include "common/pattern/stripe_width.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace physarum {
namespace {

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json vector_json(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

// {"mean", "std", "min", "max", "median", "count"} of a list (null statistics when it is empty).
nlohmann::json statistics_json(std::vector<double> values) {
  const MeanStd m = mean_and_std(values);
  nlohmann::json j{{"count", values.size()}, {"mean", number_or_null(m.mean)}, {"std", number_or_null(m.std)}};
  if (values.empty()) {
    j["min"] = j["max"] = j["median"] = nullptr;
    return j;
  }
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  j["min"] = values.front();
  j["max"] = values.back();
  j["median"] = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  return j;
}

}  // namespace

MeanStd mean_and_std(const std::vector<double>& values) {
  if (values.empty()) return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= static_cast<double>(values.size());
  double variance = 0.0;
  for (double v : values) variance += (v - mean) * (v - mean);
  return {mean, std::sqrt(variance / static_cast<double>(values.size()))};
}

PatternAnalysis analyze_pattern(const InputMesh& mesh, const InputVertexData<double>& field,
                                const PatternAnalysisOptions& options) {
  PatternAnalysis a;
  a.threshold_given = options.threshold.has_value();
  a.below = options.below;
  if (!(options.min_area >= 0.0) || !std::isfinite(options.min_area))
    throw InputError(mesh.source + ": the minimum region area must be a finite number >= 0");
  a.min_area = options.min_area;
  // Below the threshold is above it for the negated field.
  const double sign = options.below ? -1.0 : 1.0;
  InputVertexData<double> segmented = field;
  for (size_t v = 0; v < segmented.size(); ++v) segmented[v] *= sign;
  const double threshold = options.threshold ? sign * *options.threshold : default_pattern_threshold(mesh, segmented);
  a.threshold = sign * threshold;
  const PatternSegmentation segmentation = segment_pattern(mesh, segmented, threshold);
  a.field_min = *std::min_element(field.values().begin(), field.values().end());
  a.field_max = *std::max_element(field.values().begin(), field.values().end());
  if (segmentation.regions.empty()) {
    const std::string why = a.field_min == a.field_max ? "the field is constant (" + std::to_string(a.field_min) + ")"
                            : options.below            ? "its minimum is " + std::to_string(a.field_min)
                                                       : "its maximum is " + std::to_string(a.field_max);
    throw InputError(mesh.source + ": nothing to segment: no value is " + (options.below ? "below" : "above") +
                     " the threshold " + std::to_string(a.threshold) + " (" + why + ")");
  }
  for (const auto& t : mesh.triangles) {
    const auto& p = mesh.positions;
    a.surface_area += 0.5 * (p[static_cast<size_t>(t[1])] - p[static_cast<size_t>(t[0])])
                                .cross(p[static_cast<size_t>(t[2])] - p[static_cast<size_t>(t[0])])
                                .norm();
  }

  std::vector<SpotShape> spot_shapes;  // of the spots (not stripes), for the spacing
  std::vector<int> spot_region;
  for (const PatternRegion& region : segmentation.regions) {
    if (!(region.area > 0.0)) continue;  // a single vertex exactly grazing the threshold's level
    if (region.area < options.min_area) {
      ++a.dropped_regions;
      continue;
    }
    AnalysedRegion r;
    r.area = region.area;
    r.shape = spot_shape(mesh, region);
    r.contour_length = region.contour_length;
    r.holes = region.hole_count();
    r.touches_boundary = region.touches_boundary;
    r.is_stripe = is_stripe(region, r.shape.aspect_ratio);
    if (r.is_stripe) r.stripe_width = stripe_width(region);
    if (options.direction) r.direction_angle_deg = angle_to_direction_deg(r.shape, options.direction->at(r.shape.centre));
    if (!r.is_stripe) {
      spot_shapes.push_back(r.shape);
      spot_region.push_back(static_cast<int>(a.regions.size()));
    }
    a.regions.push_back(r);
  }
  for (SpotPair p : neighbouring_spot_pairs(mesh, spot_shapes)) {
    p.a = spot_region[static_cast<size_t>(p.a)];
    p.b = spot_region[static_cast<size_t>(p.b)];
    a.pairs.push_back(p);
  }
  return a;
}

nlohmann::json pattern_analysis_json(const PatternAnalysis& a, const std::string& field_name) {
  std::vector<int> neighbour_count(a.regions.size(), 0);
  for (const SpotPair& p : a.pairs) {
    ++neighbour_count[static_cast<size_t>(p.a)];
    ++neighbour_count[static_cast<size_t>(p.b)];
  }
  nlohmann::json spots = nlohmann::json::array();
  std::vector<double> areas, aspects, widths, direction_angles, spacings;
  // Spots clear of the surface's boundary: whole spots, whose area a cut one does not bias (what a
  // sketch's ellipses are compared with, common/sketch/).
  std::vector<double> interior_spot_areas;
  std::complex<double> axial(0.0, 0.0);  // mean of exp(2i theta): orientations are lines, not arrows
  int spot_count = 0, stripe_count = 0;
  double covered = 0.0;
  for (size_t i = 0; i < a.regions.size(); ++i) {
    const AnalysedRegion& r = a.regions[i];
    const SpotShape& s = r.shape;
    covered += r.area;
    (r.is_stripe ? stripe_count : spot_count) += 1;
    areas.push_back(r.area);
    if (!r.is_stripe && !r.touches_boundary) interior_spot_areas.push_back(r.area);
    if (std::isfinite(s.aspect_ratio)) aspects.push_back(s.aspect_ratio);
    if (r.stripe_width) widths.push_back(*r.stripe_width);
    if (r.direction_angle_deg) direction_angles.push_back(*r.direction_angle_deg);
    axial += std::polar(1.0, 2.0 * s.orientation_deg * M_PI / 180.0);
    nlohmann::json j{{"index", i},
                     {"kind", r.is_stripe ? "stripe" : "spot"},
                     {"area", r.area},
                     {"equivalent_diameter", 2.0 * std::sqrt(r.area / M_PI)},
                     {"centroid", vector_json(s.centre)},
                     {"normal", vector_json(s.normal)},
                     {"aspect_ratio", number_or_null(s.aspect_ratio)},
                     {"orientation_deg", s.orientation_deg},
                     {"major_axis", vector_json(s.major_axis)},
                     {"major_length", s.major_length},
                     {"minor_length", s.minor_length},
                     {"contour_length", r.contour_length},
                     {"holes", r.holes},
                     {"touches_boundary", r.touches_boundary},
                     {"neighbours", neighbour_count[i]},
                     {"stripe_width", r.stripe_width ? nlohmann::json(*r.stripe_width) : nlohmann::json(nullptr)}};
    if (r.direction_angle_deg) j["direction_angle_deg"] = *r.direction_angle_deg;
    spots.push_back(j);
  }
  nlohmann::json pairs = nlohmann::json::array();
  for (const SpotPair& p : a.pairs) {
    pairs.push_back({p.a, p.b, p.distance});
    spacings.push_back(p.distance);
  }
  const MeanStd spacing = mean_and_std(spacings), width = mean_and_std(widths);
  axial /= static_cast<double>(std::max<size_t>(a.regions.size(), 1));
  double mean_orientation = std::arg(axial) * 90.0 / M_PI;
  if (mean_orientation < 0.0) mean_orientation += 180.0;

  nlohmann::json summary{{"surface_area", a.surface_area},
                         {"covered_area", covered},
                         {"coverage", covered / a.surface_area},
                         {"spot_density", static_cast<double>(spot_count) / a.surface_area},
                         {"field_min", a.field_min},
                         {"field_max", a.field_max},
                         {"area", statistics_json(areas)},
                         {"interior_spot_area", statistics_json(interior_spot_areas)},
                         {"aspect_ratio", statistics_json(aspects)},
                         {"orientation", {{"mean_deg", mean_orientation}, {"order", std::abs(axial)}}}};
  if (!direction_angles.empty()) summary["direction_angle_deg"] = statistics_json(direction_angles);
  return nlohmann::json{
      {"field", field_name},
      {"threshold", a.threshold},
      {"threshold_rule", a.threshold_given ? "given (--threshold)"
                         : a.below         ? "area-weighted mean - 0.5 std"
                                           : "area-weighted mean + 0.5 std"},
      {"regions_are", a.below ? "below the threshold" : "above the threshold"},
      {"spot_count", spot_count},
      {"stripe_count", stripe_count},
      {"region_count", a.regions.size()},
      {"min_area", a.min_area},
      {"dropped_regions", a.dropped_regions},
      {"spots", spots},
      {"spacing", {{"mean", number_or_null(spacing.mean)}, {"std", number_or_null(spacing.std)},
                   {"median", statistics_json(spacings)["median"]}, {"count", spacings.size()}, {"pairs", pairs}}},
      {"stripe_width", {{"mean", number_or_null(width.mean)}, {"std", number_or_null(width.std)}, {"count", widths.size()}}},
      {"summary", summary}};
}

}  // namespace physarum
