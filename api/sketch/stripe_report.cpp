#include "api/sketch/stripe_report.hpp"

#include "common/sketch/median.hpp"
#include "api/sketch/sketch_report.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace physarum {
namespace {

// The gradient of the linear interpolant of f over a triangle, and the triangle's area.
Eigen::Vector3d face_gradient(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, double f0,
                              double f1, double f2, double& area) {
  const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
  const double twice_area = n.norm();
  area = 0.5 * twice_area;
  if (!(twice_area > 0.0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d u = n / twice_area;
  // grad f = sum_i f_i (u x e_i) / (2 A), e_i the edge opposite vertex i.
  return (f0 * u.cross(p2 - p1) + f1 * u.cross(p0 - p2) + f2 * u.cross(p1 - p0)) / twice_area;
}

}  // namespace

std::vector<StripeMeasure> measure_stripes(const InputMesh& mesh, const std::vector<double>& field,
                                           const PatternAnalysis& analysis, const SketchRegions& regions,
                                           const SketchDomain& domain) {
  const size_t n = regions.regions.size();
  std::vector<Eigen::Matrix2d> tensor(n, Eigen::Matrix2d::Zero());
  for (const auto& t : mesh.triangles) {
    const auto i = [&](int k) { return static_cast<size_t>(t[static_cast<size_t>(k)]); };
    double area = 0.0;
    const Eigen::Vector3d g = face_gradient(mesh.positions[i(0)], mesh.positions[i(1)], mesh.positions[i(2)],
                                            field[i(0)], field[i(1)], field[i(2)], area);
    const Eigen::Vector3d centroid = (mesh.positions[i(0)] + mesh.positions[i(1)] + mesh.positions[i(2)]) / 3.0;
    const SketchDomain::Located at = domain.locate(centroid);
    // The gradient in the window's frame (the chain rule through the window's map there; up to the
    // metres per input unit, one factor for every face).
    const Eigen::Vector2d gw = at.frame.stretch.transpose() * (at.frame.frame.transpose() * g);
    tensor[static_cast<size_t>(regions.region_of(at.window_point))] += area * gw * gw.transpose();
  }
  std::vector<std::vector<double>> widths(n);
  for (const AnalysedRegion& r : analysis.regions)
    if (r.is_stripe && r.stripe_width)
      widths[static_cast<size_t>(regions.region_of(domain.locate(r.shape.centre).window_point))].push_back(*r.stripe_width *
                                                                                                           domain.scale());
  std::vector<StripeMeasure> measures(n);
  for (size_t k = 0; k < n; ++k) {
    const Eigen::Matrix2d& J = tensor[k];
    const double across = 0.5 * std::atan2(2.0 * J(0, 1), J(0, 0) - J(1, 1)) * 180.0 / M_PI;
    measures[k].orientation = std::fmod(across + 90.0 + 360.0, 180.0);
    const double trace = J.trace();
    measures[k].coherence = trace > 0.0 ? std::hypot(J(0, 0) - J(1, 1), 2.0 * J(0, 1)) / trace : 0.0;
    measures[k].stripes = static_cast<int>(widths[k].size());
    measures[k].width = median(widths[k]);
  }
  return measures;
}

double width_miss(const StripeMeasure& generated, double sketched_width) {
  return generated.stripes > 0 ? generated.width / sketched_width - 1.0 : std::numeric_limits<double>::infinity();
}

nlohmann::ordered_json stripe_region_report(const RegionAttributes& sketched, double sketched_width_m,
                                            const StripeMeasure& generated, const SketchDomain& domain) {
  const double s = domain.scale();
  const double miss = width_miss(generated, sketched_width_m);
  return {{"center", center_json(domain, sketched.center)},
          {"sketched_strokes", sketched.strokes},
          {"sketched", {{"orientation", sketched.orientation}, {"width", sketched_width_m / s}}},
          {"generated",
           {{"stripes", generated.stripes},
            {"orientation", generated.orientation},
            {"coherence", generated.coherence},
            {"width", generated.stripes > 0 ? nlohmann::ordered_json(generated.width / s) : nlohmann::ordered_json(nullptr)}}},
          {"verdict",
           {{"orientation", axis_difference(generated.orientation, sketched.orientation) <= kStripeOrientationTolerance ? "pass" : "miss"},
            {"width", generated.stripes == 0 ? "no stripes" : std::abs(miss) <= kWidthTolerance ? "pass" : "miss"}}}};
}

}  // namespace physarum
