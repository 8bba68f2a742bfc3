#include "common/sketch/sketch_domain.hpp"

#include "common/base/errors.hpp"
#include "common/base/value_range.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace physarum {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

// The triangle (a, b, c)'s barycentric coordinates of p in the plane; nothing for a degenerate one.
std::optional<Eigen::Vector3d> barycentric_2d(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                              const Eigen::Vector2d& c) {
  Eigen::Matrix2d edges;
  edges << b - a, c - a;
  const double det = edges.determinant();
  if (!(std::abs(det) > 0.0)) return std::nullopt;
  const Eigen::Vector2d vw = edges.inverse() * (p - a);
  return Eigen::Vector3d(1.0 - vw.x() - vw.y(), vw.x(), vw.y());
}

// The frame of a face from its window-to-metres Jacobian J (3 x 2): J's columns orthonormalised
// (Gram-Schmidt) give the tangent basis, the stretch is J in that basis (upper triangular).
// The UV charts: faces joined across every edge whose two ends have the same UVs on both sides
// (union-find), numbered in order of their first face.
std::vector<int> uv_charts(const InputMesh& mesh) {
  std::vector<int> parent(mesh.triangles.size());
  for (size_t f = 0; f < parent.size(); ++f) parent[f] = static_cast<int>(f);
  auto root = [&](int f) {
    while (parent[static_cast<size_t>(f)] != f) f = parent[static_cast<size_t>(f)] = parent[static_cast<size_t>(parent[static_cast<size_t>(f)])];
    return f;
  };
  std::map<std::pair<int, int>, int> edge_face;  // a UV edge (ends in order) -> the first face seen with it
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.triangle_uvs[f][static_cast<size_t>(c)], b = mesh.triangle_uvs[f][static_cast<size_t>((c + 1) % 3)];
      const auto [it, inserted] = edge_face.try_emplace({std::min(a, b), std::max(a, b)}, static_cast<int>(f));
      if (!inserted) parent[static_cast<size_t>(root(static_cast<int>(f)))] = root(it->second);
    }
  std::vector<int> chart(mesh.triangles.size()), number(mesh.triangles.size(), -1);
  int charts = 0;
  for (size_t f = 0; f < chart.size(); ++f) {
    int& n = number[static_cast<size_t>(root(static_cast<int>(f)))];
    if (n < 0) n = charts++;
    chart[f] = n;
  }
  return chart;
}

WindowFrame frame_from_jacobian(const Eigen::Matrix<double, 3, 2>& J) {
  WindowFrame f;
  const Eigen::Vector3d e1 = J.col(0).normalized();
  const Eigen::Vector3d e2 = (J.col(1) - e1.dot(J.col(1)) * e1).normalized();
  f.frame << e1, e2;
  f.stretch = f.frame.transpose() * J;
  return f;
}

}  // namespace

double WindowFrame::area_factor() const { return std::abs(stretch.determinant()); }
double WindowFrame::length_factor() const { return std::sqrt(area_factor()); }
Eigen::Vector3d WindowFrame::to_surface(const Eigen::Vector2d& w) const { return frame * (stretch * w); }

Eigen::Matrix2d shape_tensor(double aspect, double degrees) {
  const Eigen::Vector2d d(std::cos(degrees / kDegrees), std::sin(degrees / kDegrees)), n(-d.y(), d.x());
  return d * d.transpose() + aspect * aspect * n * n.transpose();
}

EllipseShape ellipse_shape(const Eigen::Matrix2d& t) {
  // The eigenvalues and the major eigenvector's angle of a symmetric 2 x 2 matrix in closed form.
  const double mean = 0.5 * (t(0, 0) + t(1, 1)), half_gap = std::hypot(0.5 * (t(0, 0) - t(1, 1)), t(0, 1));
  const double major = mean + half_gap, minor = std::max(mean - half_gap, 0.0);
  EllipseShape e;
  e.aspect = major > 0.0 ? std::sqrt(minor / major) : 1.0;
  e.orientation = std::fmod(0.5 * std::atan2(2.0 * t(0, 1), t(0, 0) - t(1, 1)) * kDegrees + 180.0, 180.0);
  return e;
}

EllipseShape on_surface(const WindowFrame& at, const EllipseShape& w) {
  return ellipse_shape(at.stretch * shape_tensor(w.aspect, w.orientation) * at.stretch.transpose());
}

EllipseShape in_window(const WindowFrame& at, const EllipseShape& s) {
  const Eigen::Matrix2d back = at.stretch.inverse();
  return ellipse_shape(back * shape_tensor(s.aspect, s.orientation) * back.transpose());
}

SketchDomain::SketchDomain(const Sketch& sketch, const InputMesh& mesh, double area) : mesh_(&mesh), window_(sketch.window) {
  if (!(area > 0.0) || !std::isfinite(area))
    throw InputError("--area " + ValueRange::number(area) + ": the surface's area must be > 0 m^2");
  scale_ = std::sqrt(area / compute_statistics(mesh).area);
  surface_area_ = area;
}

SketchDomain SketchDomain::patch(const Sketch& sketch, const InputMesh& mesh, double area) {
  SketchDomain d(sketch, mesh, area);
  d.low_ = d.high_ = mesh.positions.front().head<2>();
  for (const Eigen::Vector3d& p : mesh.positions) {
    d.low_ = d.low_.cwiseMin(p.head<2>());
    d.high_ = d.high_.cwiseMax(p.head<2>());
  }
  if (!((d.high_ - d.low_).minCoeff() > 0.0))
    throw InputError(mesh.source + ": has no extent in x or y; a sketch window maps onto the mesh's x/y extent");
  d.patch_frame_.stretch = ((d.high_ - d.low_).cwiseQuotient(d.window_) * d.scale_).asDiagonal();
  return d;
}

SketchDomain SketchDomain::surface(const Sketch& sketch, const InputMesh& mesh, double area) {
  SketchDomain d(sketch, mesh, area);
  d.patch_frame_.stretch = Eigen::Matrix2d::Identity() * d.scale_;
  return d;
}

SketchDomain SketchDomain::uv(const Sketch& sketch, const InputMesh& mesh, double area) {
  if (mesh.triangle_uvs.empty())
    throw InputError(sketch.source + ": a UV sketch is painted on the mesh's UV layout, and " + mesh.source +
                     " has no texture coordinates; sketch in a window instead (without --uv), or give the mesh UVs");
  SketchDomain d(sketch, mesh, area);
  d.on_uv_ = true;
  d.locator_ = std::make_shared<FaceLocator>(mesh);
  d.face_frames_.resize(mesh.triangles.size());
  std::vector<char> degenerate(mesh.triangles.size(), 0);
  double lengths = 0.0;
  int good = 0;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    Eigen::Matrix<double, 3, 2> edges3;
    Eigen::Matrix2d edges2;
    for (int k = 1; k < 3; ++k) {
      edges3.col(k - 1) = (mesh.positions[static_cast<size_t>(t[static_cast<size_t>(k)])] - mesh.positions[static_cast<size_t>(t[0])]) * d.scale_;
      edges2.col(k - 1) = d.corner_window_point(f, k) - d.corner_window_point(f, 0);
    }
    // A UV triangle of (almost) no area, or a surface triangle of none, has no map of its own.
    const double uv_area = std::abs(edges2.determinant()), surface_area = edges3.col(0).cross(edges3.col(1)).norm();
    if (!(uv_area > 1e-14 * d.window_.prod()) || !(surface_area > 0.0)) {
      degenerate[f] = 1;
      continue;
    }
    d.face_frames_[f] = frame_from_jacobian(edges3 * edges2.inverse());
    lengths += d.face_frames_[f].length_factor();
    ++good;
  }
  d.face_chart_ = uv_charts(mesh);
  d.vertex_points_.resize(mesh.positions.size());
  d.vertex_point_charts_.resize(mesh.positions.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto v = static_cast<size_t>(mesh.triangles[f][static_cast<size_t>(c)]);
      std::vector<Eigen::Vector2d>& points = d.vertex_points_[v];
      const Eigen::Vector2d w = d.corner_window_point(f, c);
      if (std::find(points.begin(), points.end(), w) != points.end()) continue;
      points.push_back(w);
      d.vertex_point_charts_[v].push_back(d.face_chart_[f]);
    }
  if (good == 0) throw InputError(mesh.source + ": no UV triangle has an area; the UV layout cannot carry a sketch");
  // Degenerate faces: their own tangent plane, stretched as the layout is on average.
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (!degenerate[f]) continue;
    const auto& t = mesh.triangles[f];
    Eigen::Vector3d e1 = mesh.positions[static_cast<size_t>(t[1])] - mesh.positions[static_cast<size_t>(t[0])];
    if (!(e1.norm() > 0.0)) e1 = Eigen::Vector3d::UnitX();
    const Eigen::Vector3d any = std::abs(e1.normalized().x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    d.face_frames_[f].frame << e1.normalized(), e1.normalized().cross(any).normalized();
    d.face_frames_[f].stretch = Eigen::Matrix2d::Identity() * (lengths / good);
  }
  return d;
}

Eigen::Vector2d SketchDomain::corner_window_point(size_t face, int corner) const {
  if (on_uv_) return mesh_->uvs[static_cast<size_t>(mesh_->triangle_uvs[face][static_cast<size_t>(corner)])].cwiseProduct(window_);
  const Eigen::Vector3d& p = mesh_->positions[static_cast<size_t>(mesh_->triangles[face][static_cast<size_t>(corner)])];
  return (p.head<2>() - low_).cwiseQuotient(high_ - low_).cwiseProduct(window_);
}

size_t SketchDomain::uv_face(const Eigen::Vector2d& w, Eigen::Vector3d& bary) const {
  size_t nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < mesh_->triangles.size(); ++f) {
    const Eigen::Vector2d a = corner_window_point(f, 0), b = corner_window_point(f, 1), c = corner_window_point(f, 2);
    if (const auto inside = barycentric_2d(w, a, b, c); inside && inside->minCoeff() >= -1e-12) {
      bary = *inside;
      return f;
    }
    if (const double dist = ((a + b + c) / 3.0 - w).squaredNorm(); dist < best) best = dist, nearest = f;
  }
  bary = Eigen::Vector3d::Constant(1.0 / 3.0);
  return nearest;
}

WindowFrame SketchDomain::frame_at(const Eigen::Vector2d& w) const {
  if (!on_uv_) return patch_frame_;
  Eigen::Vector3d bary;
  return face_frames_[uv_face(w, bary)];
}

WindowFrame SketchDomain::frame_of_face(size_t face) const { return on_uv_ ? face_frames_[face] : patch_frame_; }

SketchDomain::Located SketchDomain::locate(const Eigen::Vector3d& p) const {
  if (!on_uv_) return {(p.head<2>() - low_).cwiseQuotient(high_ - low_).cwiseProduct(window_), patch_frame_};
  const SurfacePoint at = locator_->locate(p);
  const auto f = static_cast<size_t>(at.face);
  const Eigen::Vector2d w = at.barycentric[0] * corner_window_point(f, 0) + at.barycentric[1] * corner_window_point(f, 1) +
                            at.barycentric[2] * corner_window_point(f, 2);
  return {w, face_frames_[f]};
}

std::vector<Eigen::Vector2d> SketchDomain::vertex_window_points(size_t vertex) const {
  if (!on_uv_) return {locate(mesh_->positions[vertex]).window_point};
  return vertex_points_[vertex];
}

std::vector<int> SketchDomain::vertex_charts(size_t vertex) const {
  if (!on_uv_) return {-1};
  return vertex_point_charts_[vertex];
}

int SketchDomain::chart_at(const Eigen::Vector2d& w) const {
  if (!on_uv_) return -1;
  Eigen::Vector3d bary;
  const size_t f = uv_face(w, bary);
  const auto inside = barycentric_2d(w, corner_window_point(f, 0), corner_window_point(f, 1), corner_window_point(f, 2));
  return inside && inside->minCoeff() >= -1e-12 ? face_chart_[f] : -1;
}

Eigen::Vector2d SketchDomain::face_window_point(size_t face) const {
  return (corner_window_point(face, 0) + corner_window_point(face, 1) + corner_window_point(face, 2)) / 3.0;
}

std::optional<Eigen::Vector3d> SketchDomain::surface_point(const Eigen::Vector2d& w) const {
  if (!on_uv_) {
    const Eigen::Vector2d xy = low_ + w.cwiseQuotient(window_).cwiseProduct(high_ - low_);
    double z = 0.0, nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : mesh_->positions)
      if (const double d = (p.head<2>() - xy).squaredNorm(); d < nearest) nearest = d, z = p.z();
    return Eigen::Vector3d(xy.x(), xy.y(), z);
  }
  Eigen::Vector3d bary;
  const size_t f = uv_face(w, bary);
  const Eigen::Vector2d a = corner_window_point(f, 0), b = corner_window_point(f, 1), c = corner_window_point(f, 2);
  const auto inside = barycentric_2d(w, a, b, c);
  if (!inside || inside->minCoeff() < -1e-12) return std::nullopt;
  const auto& t = mesh_->triangles[f];
  return bary[0] * mesh_->positions[static_cast<size_t>(t[0])] + bary[1] * mesh_->positions[static_cast<size_t>(t[1])] +
         bary[2] * mesh_->positions[static_cast<size_t>(t[2])];
}

}  // namespace physarum
