#include "common/sketch/surface_marks.hpp"

#include "common/base/errors.hpp"
#include "common/base/value_range.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/map_tools/fast_marching.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {
namespace {

// Barycentric coordinates kept at least this far inside a face when a mark is inserted, so that a
// mark on an edge splits its face into three proper triangles (it moves by this share of an edge).
constexpr double kInsideFace = 1e-3;

// The power of Shepard's weights, 1 / d^p: with p = 2 the marks far away still weigh so much (on
// four marks in the quadrants of a square, the smallest and largest spots came out 27 % and 26 %
// off their marks' sizes, blended toward the others); with 4 a mark rules its own neighbourhood and
// the blend between two marks happens around the midway.
constexpr double kShepardPower = 4.0;

Eigen::Vector3d face_normal(const InputMesh& mesh, size_t f) {
  const auto& t = mesh.triangles[f];
  const Eigen::Vector3d& a = mesh.positions[static_cast<size_t>(t[0])];
  return (mesh.positions[static_cast<size_t>(t[1])] - a).cross(mesh.positions[static_cast<size_t>(t[2])] - a).normalized();
}

SurfacePoint closest_face(const InputMesh& mesh, const Eigen::Vector3d& p) { return FaceLocator(mesh).locate(p); }

// The mesh with each mark made a vertex (an existing vertex when the mark lies on one); `seeds` the
// marks' vertices.
InputMesh with_marks_as_vertices(const InputMesh& mesh, const std::vector<Eigen::Vector3d>& points, std::vector<int>& seeds) {
  InputMesh split = mesh;
  for (const Eigen::Vector3d& p : points) {
    const SurfacePoint at = closest_face(split, p);
    const auto f = static_cast<size_t>(at.face);
    const std::array<int, 3> t = split.triangles[f];
    int corner = 0;
    at.barycentric.maxCoeff(&corner);
    if (at.barycentric[corner] > 1.0 - kInsideFace) {
      seeds.push_back(t[static_cast<size_t>(corner)]);
      continue;
    }
    Eigen::Vector3d b = at.barycentric.cwiseMax(kInsideFace);
    b /= b.sum();
    const int v = split.vertex_count();
    split.positions.push_back(b[0] * split.positions[static_cast<size_t>(t[0])] + b[1] * split.positions[static_cast<size_t>(t[1])] +
                              b[2] * split.positions[static_cast<size_t>(t[2])]);
    split.file_vertex.push_back(-1);
    split.triangles[f] = {t[0], t[1], v};
    split.triangles.push_back({t[1], t[2], v});
    split.triangles.push_back({t[2], t[0], v});
    seeds.push_back(v);
  }
  split.uvs.clear();
  split.triangle_uvs.clear();
  return split;
}

std::vector<double> shepard(const std::vector<double>& d) {
  std::vector<double> w(d.size());
  double sum = 0.0;
  for (size_t k = 0; k < d.size(); ++k) sum += w[k] = 1.0 / std::max(std::pow(d[k], kShepardPower), 1e-300);
  for (double& x : w) x /= sum;
  return w;
}

}  // namespace

std::vector<double> SurfaceMarks::weights(size_t vertex) const { return shepard(distance[vertex]); }

std::vector<double> SurfaceMarks::distances(const Eigen::Vector3d& input_point) const {
  const SurfacePoint at = locator->locate(input_point);
  std::vector<double> d(size(), 0.0);
  for (int c = 0; c < 3; ++c)
    for (size_t k = 0; k < size(); ++k)
      d[k] += at.barycentric[c] * distance[static_cast<size_t>(mesh->triangles[static_cast<size_t>(at.face)][static_cast<size_t>(c)])][k];
  return d;
}

std::vector<double> SurfaceMarks::weights(const Eigen::Vector3d& input_point) const { return shepard(distances(input_point)); }

double SurfaceMarks::ellipse_radius(size_t k, const Eigen::Vector3d& input_point) const {
  const double major = std::sqrt(area[k] / (M_PI * aspect[k])), minor = aspect[k] * major;
  if (distances(input_point)[k] > 2.0 * major) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d offset = input_point - point[k];
  const double along = offset.dot(axis[k]), across = offset.dot(normal[k].cross(axis[k]));
  return std::sqrt(along * along / (major * major) + across * across / (minor * minor));
}
int SurfaceMarks::nearest(const Eigen::Vector3d& input_point) const {
  const std::vector<double> w = weights(input_point);
  return static_cast<int>(std::max_element(w.begin(), w.end()) - w.begin());
}

SurfaceMarks place_surface_marks(const Sketch& sketch, const InputMesh& mesh) {
  SurfaceMarks marks;
  marks.mesh = &mesh;
  marks.locator = std::make_shared<FaceLocator>(mesh);
  const FaceLocator& locator = *marks.locator;
  const double diagonal = bounding_box_diagonal(mesh);
  for (size_t k = 0; k < sketch.surface_spots.size(); ++k) {
    const SurfaceSpot& s = sketch.surface_spots[k];
    const std::string what = sketch.source + ": mark " + std::to_string(k);
    const SurfacePoint at = locator.locate(s.point);
    const auto& t = mesh.triangles[static_cast<size_t>(at.face)];
    const Eigen::Vector3d p = at.barycentric[0] * mesh.positions[static_cast<size_t>(t[0])] +
                              at.barycentric[1] * mesh.positions[static_cast<size_t>(t[1])] +
                              at.barycentric[2] * mesh.positions[static_cast<size_t>(t[2])];
    if ((p - s.point).norm() > 0.1 * diagonal)
      throw InputError(what + ": its surface_point lies " + ValueRange::number((p - s.point).norm()) + " from " + mesh.source +
                       "'s surface (more than a tenth of its size " + ValueRange::number(diagonal) + "): is it in the mesh's coordinates?");
    const Eigen::Vector3d n = face_normal(mesh, static_cast<size_t>(at.face));
    const Eigen::Vector3d tangent = s.direction - s.direction.dot(n) * n;
    if (!(tangent.norm() > 0.1))
      throw InputError(what + ": its direction is (nearly) normal to the surface at its point (normal " + ValueRange::number(n.x()) + ", " +
                       ValueRange::number(n.y()) + ", " + ValueRange::number(n.z()) + "); give a direction along the surface");
    marks.point.push_back(p);
    marks.normal.push_back(n);
    marks.axis.push_back(s.across ? n.cross(tangent).normalized() : tangent.normalized());
    marks.area.push_back(M_PI * s.major * s.minor);
    marks.aspect.push_back(s.minor / s.major);
  }
  std::vector<int> seeds;
  const InputMesh split = with_marks_as_vertices(mesh, marks.point, seeds);
  const SurfaceDomain domain = build_surface_domain(intrinsic_mesh_from_input(split));
  const FastMarchingGeodesics fmm(domain);
  marks.distance.assign(mesh.positions.size(), std::vector<double>(marks.size()));
  marks.spacing.assign(marks.size(), 0.0);
  for (size_t k = 0; k < marks.size(); ++k) {
    IntrinsicVertexData<double> d;
    try {
      d = fmm.distance({seeds[k]});
    } catch (const InputError&) {
      throw InputError(sketch.source + ": " + mesh.source + " has a connected piece that mark " + std::to_string(k) +
                       "'s distances cannot reach; marks on a surface of several pieces are not supported");
    }
    for (size_t v = 0; v < mesh.positions.size(); ++v) marks.distance[v][k] = d[v];
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t other = 0; other < marks.size(); ++other)
      if (other != k) nearest = std::min(nearest, d[static_cast<size_t>(seeds[other])]);
    marks.spacing[k] = std::isfinite(nearest) ? nearest : 0.0;
  }
  return marks;
}

nlohmann::ordered_json surface_marks_json(const SurfaceMarks& marks) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (size_t k = 0; k < marks.size(); ++k)
    list.push_back({{"point", {marks.point[k].x(), marks.point[k].y(), marks.point[k].z()}},
                    {"area", marks.area[k]},
                    {"aspect", marks.aspect[k]},
                    {"axis", {marks.axis[k].x(), marks.axis[k].y(), marks.axis[k].z()}},
                    {"spacing", marks.spacing[k]}});
  return list;
}

}  // namespace physarum
