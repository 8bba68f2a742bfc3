#pragma once
// The attributes of a sketch the paper's inverse map reads (004, Sec. 5.1): per spot its area (pi a b),
// shape (aspect = minor / major radius), orientation (the major axis, degrees in [0, 180)) and
// spacing (the mean distance from its centre to its Delaunay neighbours' centres, as the paper's
// Fig. 4 draws them); per stroke its orientation (its segments' directions averaged by length, as
// axes: doubled angles) and width. Lengths in window units.
#include "common/sketch/sketch.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace physarum {

struct SpotAttributes {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double area = 0.0, aspect = 1.0, orientation = 0.0;
  double spacing = 0.0;  // 0 when the spot has no neighbour (a sketch of one spot)
  std::vector<int> neighbours;  // Delaunay neighbours, by spot index
};

struct StrokeAttributes {
  double orientation = 0.0;  // degrees in [0, 180)
  double length = 0.0;
  int width_class = 1;
  double width = 0.0;  // measured (pictures), 0 for JSON strokes
};

struct SketchAttributes {
  std::vector<SpotAttributes> spots;
  std::vector<StrokeAttributes> strokes;
};

SketchAttributes measure_sketch(const Sketch& sketch);

// The Delaunay neighbours of each point (Boost.Polygon's Voronoi diagram: two sites are neighbours
// when their cells share an edge), each list ascending. Coincident points share one cell and have
// the other's neighbours.
std::vector<std::vector<int>> delaunay_neighbours(const std::vector<Eigen::Vector2d>& points);

// sketch.json's "spots" and "strokes" (../shared/DESIGN.md).
nlohmann::ordered_json sketch_attributes_json(const SketchAttributes& attributes);

}  // namespace physarum
