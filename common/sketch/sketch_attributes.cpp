#include "common/sketch/sketch_attributes.hpp"

#include <boost/polygon/voronoi.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace physarum {
namespace {

// The lengths and doubled-angle sum of a polyline's segments: the mean direction of an undirected
// line (30 and 210 degrees are the same stroke).
StrokeAttributes stroke_attributes(const SketchStroke& stroke) {
  StrokeAttributes a;
  Eigen::Vector2d doubled = Eigen::Vector2d::Zero();
  for (size_t k = 0; k + 1 < stroke.points.size(); ++k) {
    const Eigen::Vector2d d = stroke.points[k + 1] - stroke.points[k];
    const double length = d.norm(), angle = std::atan2(d.y(), d.x());
    a.length += length;
    doubled += length * Eigen::Vector2d(std::cos(2.0 * angle), std::sin(2.0 * angle));
  }
  a.orientation = axis_orientation(0.5 * std::atan2(doubled.y(), doubled.x()) * 180.0 / M_PI);
  a.width_class = stroke.width_class;
  a.width = stroke.width;
  return a;
}

}  // namespace

std::vector<std::vector<int>> delaunay_neighbours(const std::vector<Eigen::Vector2d>& points) {
  std::vector<std::vector<int>> neighbours(points.size());
  if (points.size() < 2) return neighbours;
  // Boost.Polygon's Voronoi builder takes integer sites: the points scaled onto a 2^26 grid over
  // their bounding box (a relative resolution of 1.5e-8, far below any drawn distance).
  Eigen::Vector2d lo = points[0], hi = points[0];
  for (const Eigen::Vector2d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double scale = static_cast<double>(1 << 26) / std::max((hi - lo).maxCoeff(), 1e-300);
  // Coincident points are one site (Boost.Polygon wants distinct sites) and share its neighbours.
  std::vector<boost::polygon::point_data<int>> sites;
  std::vector<int> site_of(points.size());
  std::vector<std::vector<int>> points_at;
  std::map<std::pair<int, int>, int> site_at;
  for (size_t i = 0; i < points.size(); ++i) {
    const boost::polygon::point_data<int> q(static_cast<int>(std::lround((points[i].x() - lo.x()) * scale)),
                                            static_cast<int>(std::lround((points[i].y() - lo.y()) * scale)));
    const auto [it, fresh] = site_at.emplace(std::pair{q.x(), q.y()}, static_cast<int>(sites.size()));
    site_of[i] = it->second;
    if (fresh) {
      sites.push_back(q);
      points_at.emplace_back();
    }
    points_at[static_cast<size_t>(site_of[i])].push_back(static_cast<int>(i));
  }
  std::vector<std::set<int>> site_neighbours(sites.size());
  if (sites.size() > 1) {
    boost::polygon::voronoi_diagram<double> diagram;
    boost::polygon::construct_voronoi(sites.begin(), sites.end(), &diagram);
    for (const auto& edge : diagram.edges())
      if (edge.is_primary())
        site_neighbours[edge.cell()->source_index()].insert(static_cast<int>(edge.twin()->cell()->source_index()));
  }
  for (size_t i = 0; i < points.size(); ++i) {
    std::set<int> all;
    for (const int site : site_neighbours[static_cast<size_t>(site_of[i])])
      all.insert(points_at[static_cast<size_t>(site)].begin(), points_at[static_cast<size_t>(site)].end());
    for (const int j : points_at[static_cast<size_t>(site_of[i])])
      if (j != static_cast<int>(i)) all.insert(j);
    neighbours[i].assign(all.begin(), all.end());
  }
  return neighbours;
}

SketchAttributes measure_sketch(const Sketch& sketch) {
  SketchAttributes a;
  std::vector<Eigen::Vector2d> centres;
  for (const SketchSpot& s : sketch.spots) {
    SpotAttributes spot;
    spot.center = s.center;
    spot.area = M_PI * s.major * s.minor;
    spot.aspect = s.minor / s.major;
    spot.orientation = s.orientation;
    a.spots.push_back(spot);
    centres.push_back(s.center);
  }
  const std::vector<std::vector<int>> neighbours = delaunay_neighbours(centres);
  for (size_t i = 0; i < a.spots.size(); ++i) {
    SpotAttributes& spot = a.spots[i];
    spot.neighbours = neighbours[i];
    double sum = 0.0;
    for (const int j : spot.neighbours) sum += (centres[static_cast<size_t>(j)] - spot.center).norm();
    spot.spacing = spot.neighbours.empty() ? 0.0 : sum / static_cast<double>(spot.neighbours.size());
  }
  for (const SketchStroke& s : sketch.strokes) a.strokes.push_back(stroke_attributes(s));
  return a;
}

nlohmann::ordered_json sketch_attributes_json(const SketchAttributes& attributes) {
  nlohmann::ordered_json j;
  j["spots"] = nlohmann::ordered_json::array();
  for (const SpotAttributes& s : attributes.spots)
    j["spots"].push_back({{"center", {s.center.x(), s.center.y()}},
                          {"area", s.area},
                          {"aspect", s.aspect},
                          {"orientation", s.orientation},
                          {"spacing", s.spacing},
                          {"neighbours", s.neighbours}});
  j["strokes"] = nlohmann::ordered_json::array();
  for (const StrokeAttributes& s : attributes.strokes)
    j["strokes"].push_back(
        {{"orientation", s.orientation}, {"length", s.length}, {"width_class", s.width_class}, {"width", s.width}});
  return j;
}

}  // namespace physarum
