#include "common/sketch/sketch.hpp"

#include "common/base/errors.hpp"

#include <cmath>
#include <set>

namespace physarum {
namespace {

using nlohmann::json;

class MarkReader {
 public:
  explicit MarkReader(std::string where) : where_(std::move(where)) {}

  [[noreturn]] void fail(const std::string& what) const { throw InputError(where_ + ": " + what); }

  void only(const json& object, const std::set<std::string>& fields, const std::string& what) const {
    if (!object.is_object()) fail(what + " must be an object");
    for (auto it = object.begin(); it != object.end(); ++it)
      if (!fields.count(it.key())) fail(what + ": unknown field \"" + it.key() + "\"");
  }

  double number(const json& object, const char* field, const std::string& what) const {
    const auto it = object.find(field);
    if (it == object.end()) fail(what + ": missing \"" + field + "\"");
    if (!it->is_number() || !std::isfinite(it->get<double>())) fail(what + ": \"" + field + "\" must be a finite number");
    return it->get<double>();
  }

  Eigen::Vector2d pair(const json& value, const std::string& what) const {
    if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number())
      fail(what + " = " + value.dump() + " must be two numbers");
    const Eigen::Vector2d p(value[0].get<double>(), value[1].get<double>());
    if (!p.allFinite()) fail(what + " must be finite");
    return p;
  }

  Eigen::Vector3d triple_field(const json& object, const char* field, const std::string& what) const {
    const auto it = object.find(field);
    if (it == object.end()) fail(what + ": missing \"" + field + "\"");
    const json& v = *it;
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      fail(what + " \"" + field + "\" = " + v.dump() + " must be three numbers");
    const Eigen::Vector3d p(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    if (!p.allFinite()) fail(what + " \"" + field + "\" must be finite");
    return p;
  }

  Eigen::Vector2d pair_field(const json& object, const char* field, const std::string& what) const {
    const auto it = object.find(field);
    if (it == object.end()) fail(what + ": missing \"" + field + "\"");
    return pair(*it, what + " \"" + field + "\"");
  }

 private:
  std::string where_;
};

bool inside(const Eigen::Vector2d& p, const Eigen::Vector2d& window) {
  return p.x() >= 0.0 && p.y() >= 0.0 && p.x() <= window.x() && p.y() <= window.y();
}

SketchSpot read_ellipse(const json& e, const Eigen::Vector2d& window, const MarkReader& r, const std::string& what) {
  r.only(e, {"center", "radii", "angle"}, what);
  SketchSpot spot;
  spot.center = r.pair_field(e, "center", what);
  if (!inside(spot.center, window)) r.fail(what + ": the centre lies outside the window");
  const Eigen::Vector2d radii = r.pair_field(e, "radii", what);
  if (!(radii.minCoeff() > 0.0)) r.fail(what + ": \"radii\" must both be > 0");
  const double angle = e.contains("angle") ? r.number(e, "angle", what) : 0.0;
  // The major axis is the first radius' direction, or the one across it.
  spot.major = radii.maxCoeff();
  spot.minor = radii.minCoeff();
  spot.orientation = axis_orientation(radii[0] >= radii[1] ? angle : angle + 90.0);
  return spot;
}

SurfaceSpot read_surface_ellipse(const json& e, const MarkReader& r, const std::string& what) {
  r.only(e, {"surface_point", "radii", "direction"}, what);
  SurfaceSpot spot;
  spot.point = r.triple_field(e, "surface_point", what);
  const Eigen::Vector2d radii = r.pair_field(e, "radii", what);
  if (!(radii.minCoeff() > 0.0)) r.fail(what + ": \"radii\" must both be > 0");
  spot.major = radii.maxCoeff();
  spot.minor = radii.minCoeff();
  spot.direction = r.triple_field(e, "direction", what);
  if (!(spot.direction.norm() > 0.0)) r.fail(what + ": \"direction\" must not be zero");
  spot.direction.normalize();
  spot.across = radii[0] < radii[1];
  return spot;
}

SketchStroke read_stroke(const json& s, const Eigen::Vector2d& window, const MarkReader& r, const std::string& what) {
  r.only(s, {"points", "width"}, what);
  SketchStroke stroke;
  const auto points = s.find("points");
  if (points == s.end() || !points->is_array() || points->size() < 2) r.fail(what + ": \"points\" must list two or more points");
  for (size_t k = 0; k < points->size(); ++k) {
    stroke.points.push_back(r.pair((*points)[k], what + " point " + std::to_string(k)));
    if (!inside(stroke.points.back(), window)) r.fail(what + " point " + std::to_string(k) + " lies outside the window");
  }
  if ((stroke.points.back() - stroke.points.front()).norm() == 0.0 && stroke.points.size() == 2)
    r.fail(what + ": its two points are the same");
  const double width = s.contains("width") ? r.number(s, "width", what) : 1.0;
  if (width != std::floor(width) || width < 1 || width > kStrokeWidthClasses)
    r.fail(what + ": \"width\" " + s["width"].dump() + " must be a width class 1.." + std::to_string(kStrokeWidthClasses));
  stroke.width_class = static_cast<int>(width);
  return stroke;
}

}  // namespace

double axis_orientation(double degrees) {
  const double a = std::fmod(degrees, 180.0);
  return a < 0.0 ? a + 180.0 : a;
}

Sketch sketch_from_json(const json& j, const std::string& where) {
  const MarkReader r(where);
  r.only(j, {"window", "marks"}, "the sketch");
  Sketch sketch;
  sketch.source = where;
  if (j.contains("window")) sketch.window = r.pair(j["window"], "\"window\"");
  if (!(sketch.window.minCoeff() > 0.0)) r.fail("\"window\" must be two sizes > 0");
  const auto marks = j.find("marks");
  if (marks == j.end() || !marks->is_array() || marks->empty()) r.fail("the sketch has no \"marks\" (ellipses or strokes)");
  for (size_t k = 0; k < marks->size(); ++k) {
    const json& mark = (*marks)[k];
    const std::string what = "mark " + std::to_string(k);
    if (!mark.is_object() || mark.size() != 1) r.fail(what + " must be {\"ellipse\": {...}} or {\"stroke\": {...}}");
    if (mark.contains("ellipse") && mark["ellipse"].is_object() && mark["ellipse"].contains("surface_point"))
      sketch.surface_spots.push_back(read_surface_ellipse(mark["ellipse"], r, what));
    else if (mark.contains("ellipse")) sketch.spots.push_back(read_ellipse(mark["ellipse"], sketch.window, r, what));
    else if (mark.contains("stroke")) sketch.strokes.push_back(read_stroke(mark["stroke"], sketch.window, r, what));
    else r.fail(what + ": unknown kind \"" + mark.begin().key() + "\" (ellipse or stroke)");
  }
  if (!sketch.surface_spots.empty() && (!sketch.spots.empty() || !sketch.strokes.empty()))
    r.fail("the sketch mixes marks on the surface (\"surface_point\") with marks in the window: give one kind");
  return sketch;
}

}  // namespace physarum
