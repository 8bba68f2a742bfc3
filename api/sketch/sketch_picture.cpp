#include "api/sketch/sketch_picture.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

bool inside_ellipse(const SketchSpot& s, const Eigen::Vector2d& p) {
  const double a = s.orientation * M_PI / 180.0;
  const Eigen::Vector2d d = p - s.center;
  const double u = d.x() * std::cos(a) + d.y() * std::sin(a), v = -d.x() * std::sin(a) + d.y() * std::cos(a);
  return (u * u) / (s.major * s.major) + (v * v) / (s.minor * s.minor) <= 1.0;
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// A stroke's drawn half-width: its measured width, or its class as a share of the window (the
// widths sketch_image reads back as that class: 1 % of the window's shorter side per class).
double half_width(const SketchStroke& s, const Eigen::Vector2d& window) {
  return 0.5 * (s.width > 0.0 ? s.width : 0.01 * s.width_class * window.minCoeff());
}

// The pixels the mesh's UV triangles cover (the window onto UV [0, 1]^2), set to `grey`.
void draw_charts(RgbImage& image, const InputMesh& mesh, unsigned char grey) {
  auto pixel = [&](const Eigen::Vector2d& uv) { return Eigen::Vector2d(uv.x() * image.width, (1.0 - uv.y()) * image.height); };
  for (const auto& t : mesh.triangle_uvs) {
    const Eigen::Vector2d a = pixel(mesh.uvs[static_cast<size_t>(t[0])]), b = pixel(mesh.uvs[static_cast<size_t>(t[1])]),
                          c = pixel(mesh.uvs[static_cast<size_t>(t[2])]);
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (!(std::abs(area) > 0.0)) continue;
    const Eigen::Vector2d low = a.cwiseMin(b).cwiseMin(c), high = a.cwiseMax(b).cwiseMax(c);
    for (int row = std::max(0, static_cast<int>(low.y())); row <= std::min(image.height - 1, static_cast<int>(high.y())); ++row)
      for (int column = std::max(0, static_cast<int>(low.x())); column <= std::min(image.width - 1, static_cast<int>(high.x())); ++column) {
        const Eigen::Vector2d p(column + 0.5, row + 0.5);
        auto side = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return ((v - u).x() * (p - u).y() - (v - u).y() * (p - u).x()) / area; };
        if (side(a, b) >= 0.0 && side(b, c) >= 0.0 && side(c, a) >= 0.0)
          std::fill_n(image.pixels.begin() + (static_cast<ptrdiff_t>(row) * image.width + column) * 3, 3, grey);
      }
  }
}

}  // namespace

RgbImage draw_sketch(const Sketch& sketch, const InputMesh* uv_layout, int size) {
  const double unit = size / sketch.window.maxCoeff();  // pixels per window unit
  RgbImage image;
  image.width = std::max(1, static_cast<int>(std::lround(sketch.window.x() * unit)));
  image.height = std::max(1, static_cast<int>(std::lround(sketch.window.y() * unit)));
  image.pixels.assign(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3, 255);
  if (uv_layout) draw_charts(image, *uv_layout, 230);
  for (int row = 0; row < image.height; ++row)
    for (int column = 0; column < image.width; ++column) {
      // The top row is the window's largest y.
      const Eigen::Vector2d p((column + 0.5) / unit, (image.height - row - 0.5) / unit);
      bool ink = std::any_of(sketch.spots.begin(), sketch.spots.end(), [&](const SketchSpot& s) { return inside_ellipse(s, p); });
      for (const SketchStroke& s : sketch.strokes)
        for (size_t k = 0; !ink && k + 1 < s.points.size(); ++k)
          ink = distance_to_segment(p, s.points[k], s.points[k + 1]) <= half_width(s, sketch.window);
      if (ink) std::fill_n(image.pixels.begin() + (static_cast<ptrdiff_t>(row) * image.width + column) * 3, 3, 0);
    }
  return image;
}

RgbImage draw_surface_marks(const SurfaceMarks& marks, const InputMesh& surface) {
  InputVertexData<double> ink(surface.positions.size(), 0.0);
  // Full ink inside 0.8 of a mark's rim, none beyond 1.2: interpolated over the faces, the rim is
  // drawn smoothly at 1 rather than along the mesh's edges.
  for (size_t v = 0; v < surface.positions.size(); ++v)
    for (size_t k = 0; k < marks.size(); ++k)
      ink[v] = std::max(ink[v], std::clamp((1.2 - marks.ellipse_radius(k, surface.positions[v])) / 0.4, 0.0, 1.0));
  PreviewOptions options;
  options.coloring.map = ColorMap("marks", {{0.0, {0.92, 0.92, 0.92}}, {1.0, {0.0, 0.0, 0.0}}});
  options.coloring.high = 1.0;
  return render_preview(surface, ink, options);
}

}  // namespace physarum
