#include "api/sketch/sketch_report.hpp"

#include "common/sketch/median.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {
namespace {

const char* within(double miss, double tolerance) { return std::abs(miss) <= tolerance ? "pass" : "miss"; }

// A spot's ellipse as it would have been drawn in the window: its surface ellipse (major axis in the
// map's tangent basis) pulled back through the window's map there.
EllipseShape drawn_shape(const SpotShape& spot, const WindowFrame& at) {
  const Eigen::Vector2d axis = at.frame.transpose() * spot.major_axis;
  return in_window(at, {1.0 / spot.aspect_ratio, std::atan2(axis.y(), axis.x()) * 180.0 / M_PI});
}

}  // namespace

std::vector<RegionMeasure> measure_regions(const PatternAnalysis& analysis, const SketchRegions& regions,
                                           const SketchDomain& domain, const std::vector<char>& first_layer) {
  const size_t n = regions.regions.size();
  std::vector<std::vector<double>> area(n), aspect(n), orientation(n), spacing(n);
  std::vector<int> region_of(analysis.regions.size(), -1);
  const double area_scale = domain.scale() * domain.scale();
  for (size_t i = 0; i < analysis.regions.size(); ++i) {
    const AnalysedRegion& r = analysis.regions[i];
    if (r.is_stripe || r.touches_boundary) continue;
    if (!first_layer.empty() && r.shape.centre_vertex >= 0 && first_layer[static_cast<size_t>(r.shape.centre_vertex)]) continue;
    int k = 0;
    EllipseShape drawn;
    if (regions.marks) {
      // Marks on the surface: the nearest mark's region, the orientation as the angle from its axis.
      k = regions.marks->nearest(r.shape.centre);
      drawn = {1.0 / r.shape.aspect_ratio,
               angle_to_direction_deg(r.shape, regions.marks->axis[static_cast<size_t>(k)]).value_or(90.0)};
    } else {
      const SketchDomain::Located at = domain.locate(r.shape.centre);
      k = regions.region_of(at.window_point);
      drawn = drawn_shape(r.shape, at.frame);
    }
    region_of[i] = k;
    area[static_cast<size_t>(k)].push_back(r.area * area_scale);
    aspect[static_cast<size_t>(k)].push_back(drawn.aspect);
    orientation[static_cast<size_t>(k)].push_back(drawn.orientation);
  }
  for (const SpotPair& p : analysis.pairs) {
    const int a = region_of[static_cast<size_t>(p.a)], b = region_of[static_cast<size_t>(p.b)];
    if (a >= 0 && a == b) spacing[static_cast<size_t>(a)].push_back(p.distance * domain.scale());
  }
  std::vector<RegionMeasure> measures(n);
  for (size_t k = 0; k < n; ++k) {
    measures[k].spots = static_cast<int>(area[k].size());
    measures[k].area = median(area[k]);
    measures[k].aspect = median(aspect[k]);
    measures[k].orientation = axial_mean_degrees(orientation[k]);
    measures[k].spacing = median(spacing[k]);
  }
  return measures;
}

double area_miss(const RegionMeasure& generated, double sketched_area) {
  return generated.spots > 0 ? generated.area / sketched_area - 1.0 : std::numeric_limits<double>::infinity();
}

nlohmann::ordered_json center_json(const SketchDomain& domain, const Eigen::Vector2d& window_point) {
  const std::optional<Eigen::Vector3d> p = domain.surface_point(window_point);
  if (!p) return nullptr;
  if (!domain.on_uv()) return {p->x(), p->y()};
  return {p->x(), p->y(), p->z()};
}

double axis_difference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

nlohmann::ordered_json region_report(const RegionAttributes& sketched, double sketched_area_m2, double sketched_spacing_m,
                                     const RegionMeasure& generated, const nlohmann::ordered_json& center, double scale,
                                     bool shaped) {
  nlohmann::ordered_json verdict;
  if (generated.spots == 0) {
    verdict = {{"area", "no spots"}, {"spacing", "no spots"}, {"aspect", "no spots"}, {"orientation", "no spots"}};
  } else {
    verdict["area"] = within(area_miss(generated, sketched_area_m2), kAreaTolerance);
    verdict["spacing"] = sketched_spacing_m > 0.0 && generated.spacing > 0.0
                             ? within(generated.spacing / sketched_spacing_m - 1.0, kSpacingTolerance)
                             : "not measured";
    verdict["aspect"] = shaped ? within(generated.aspect - sketched.aspect, kAspectTolerance) : "not controlled";
    verdict["orientation"] = !shaped                                ? "not controlled"
                             : sketched.aspect > kOrientedAspect ? "round: not judged"
                                                                  : within(axis_difference(generated.orientation, sketched.orientation),
                                                                           kOrientationTolerance);
  }
  // Lengths in the input mesh's units, as `physarum analyze` reports them (../shared/DESIGN.md).
  const double s = scale;
  auto length_or_null = [s](double metres) {
    return metres > 0.0 ? nlohmann::ordered_json(metres / s) : nlohmann::ordered_json(nullptr);
  };
  auto area_or_null = [s](bool any, double m2) { return any ? nlohmann::ordered_json(m2 / (s * s)) : nlohmann::ordered_json(nullptr); };
  auto or_null = [](bool any, double x) { return any ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr); };
  const bool any = generated.spots > 0;
  return {{"center", center},
          {"sketched_spots", sketched.spots},
          {"sketched",
           {{"area", sketched_area_m2 / (s * s)},
            {"aspect", sketched.aspect},
            {"orientation", sketched.orientation},
            {"spacing", length_or_null(sketched_spacing_m)}}},
          {"generated",
           {{"spots", generated.spots},
            {"area", area_or_null(any, generated.area)},
            {"aspect", or_null(any, generated.aspect)},
            {"orientation", or_null(any, generated.orientation)},
            {"spacing", length_or_null(generated.spacing)}}},
          {"verdict", verdict}};
}

}  // namespace physarum
