#pragma once
// A sketch (`physarum sketch`, paper 004, Phan & Grimm): the spots and strokes a user drew in a sketch
// window, before any surface is involved. Window coordinates: x to the right, y up, the window
// [0, w] x [0, h]; angles in degrees counterclockwise from +x. A sketch comes from a JSON file of
// explicit marks or from a picture (common/sketch/sketch_image.hpp); its measured attributes are
// common/sketch/sketch_attributes.hpp's.
//
// The JSON form (../shared/DESIGN.md, "Wave 3 contracts"):
//   {"window": [1.0, 1.0],
//    "marks": [{"ellipse": {"center": [0.2, 0.3], "radii": [0.04, 0.02], "angle": 30.0}},
//              {"stroke": {"points": [[0.1, 0.8], [0.6, 0.9]], "width": 2}}]}
// radii are the two semi-axes (either order), angle the direction of the first one; a stroke is a
// polyline of two or more points with a width class 1..4 (the paper's four line sizes).
// A mark on a mesh's surface, {"ellipse": {"surface_point": [x, y, z], "radii": [a, b], "direction":
// [dx, dy, dz]}}, is in the input mesh's coordinates and units: the point is projected onto the
// surface and the direction (the first radius') into its tangent plane there (common/sketch/
// surface_marks.hpp). A sketch's marks are all in the window or all on the surface.
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace physarum {

// A drawn spot as an ellipse.
struct SketchSpot {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double major = 0.0;        // semi-axes, major >= minor > 0
  double minor = 0.0;
  double orientation = 0.0;  // degrees in [0, 180): the major axis' direction
};

// A drawn line.
struct SketchStroke {
  std::vector<Eigen::Vector2d> points;  // two or more
  int width_class = 1;                  // 1..4 (JSON); from a picture: the nearest class to `width`
  double width = 0.0;                   // measured line width in window units (pictures; 0 for JSON)
};

// A spot drawn on a mesh's surface (input coordinates and units), before it is projected onto it.
struct SurfaceSpot {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double major = 0.0, minor = 0.0;                       // semi-axes, major >= minor > 0
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // the first radius', unit
  bool across = false;  // the first radius is the minor one: the major axis lies across `direction`
};

struct Sketch {
  Eigen::Vector2d window = Eigen::Vector2d::Ones();  // w, h > 0
  std::vector<SketchSpot> spots;
  std::vector<SketchStroke> strokes;
  std::vector<SurfaceSpot> surface_spots;  // marks on the surface (then no window marks)
  std::string source;  // the file, for messages
};

// The stroke width classes of the paper's interface.
constexpr int kStrokeWidthClasses = 4;
// A stroke of width class k asks for stripes k x this fraction of the window's width wide (drawn in a
// picture, a class-k pen is k x 0.01 of the width: common/sketch/sketch_image.cpp).
constexpr double kStripeWidthPerClass = 0.025;

// Reads the JSON form. InputError naming `where` and the mark (by index) for anything wrong: a
// missing or non-positive window, an ellipse without positive radii, a centre outside the window, a
// stroke of fewer than two points or a width class outside 1..4, an unknown field or kind of mark,
// a surface mark without a non-zero "direction", marks of both kinds, and a sketch without marks.
Sketch sketch_from_json(const nlohmann::json& j, const std::string& where);

// A spot's orientation (degrees) brought into [0, 180): an ellipse is the same turned by 180.
double axis_orientation(double degrees);

}  // namespace physarum
