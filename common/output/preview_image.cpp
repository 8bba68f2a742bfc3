#include "common/output/preview_image.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"

#include <OpenImageIO/imageio.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace physarum {
namespace {

void check_values(const InputMesh& mesh, const InputVertexData<double>& values) {
  if (static_cast<int>(values.size()) != mesh.vertex_count())
    throw InputError("preview of " + mesh.source + ": " + std::to_string(values.size()) + " values for " +
                     std::to_string(mesh.vertex_count()) + " vertices");
}

// The rasteriser shared by every preview: `surface_colour(triangle, w0, w1, w2)` gives the unshaded
// colour (components in [0, 1]) at barycentric point w of a triangle, shading is applied here.
template <class SurfaceColour>
RgbImage render_shaded(const InputMesh& mesh, const PreviewOptions& options, const SurfaceColour& surface_colour) {
  if (options.width < 1 || options.height < 1 || options.width > 16384 || options.height > 16384)
    throw InputError("preview: image size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                     " is out of range (1..16384 each)");
  RgbImage image;
  image.width = options.width;
  image.height = options.height;
  image.pixels.resize(static_cast<size_t>(image.width) * image.height * 3);
  for (size_t p = 0; p < image.pixels.size(); p += 3)
    std::copy(options.background.begin(), options.background.end(), image.pixels.begin() + static_cast<long>(p));
  if (mesh.vertex_count() == 0) return image;

  // Orthographic camera: `toward_camera` points from the scene to the eye.
  constexpr double kDegree = std::numbers::pi / 180.0;
  const double az = options.azimuth_deg * kDegree, el = options.elevation_deg * kDegree;
  const Eigen::Vector3d toward_camera(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  const Eigen::Vector3d right = Eigen::Vector3d::UnitY().cross(toward_camera).normalized();
  const Eigen::Vector3d up = toward_camera.cross(right);
  // Light from over the viewer's left shoulder, so silhouettes facing the camera are lit.
  const Eigen::Vector3d light = (toward_camera + 0.6 * up - 0.4 * right).normalized();

  // Fit the projected mesh into the picture with a margin.
  const size_t nv = static_cast<size_t>(mesh.vertex_count());
  std::vector<Eigen::Vector3d> view(nv);  // (screen x, screen y, depth toward camera)
  Eigen::Vector2d low(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Eigen::Vector2d high = -low;
  for (size_t v = 0; v < nv; ++v) {
    const Eigen::Vector3d& p = mesh.positions[v];
    view[v] = {p.dot(right), p.dot(up), p.dot(toward_camera)};
    low = low.cwiseMin(view[v].head<2>());
    high = high.cwiseMax(view[v].head<2>());
  }
  const Eigen::Vector2d extent = (high - low).cwiseMax(1e-300);
  const double margin = 0.9;
  const double scale = std::min(margin * image.width / extent.x(), margin * image.height / extent.y());
  const Eigen::Vector2d centre = 0.5 * (low + high);
  for (auto& q : view) {
    q.x() = 0.5 * image.width + scale * (q.x() - centre.x());
    q.y() = 0.5 * image.height - scale * (q.y() - centre.y());  // image rows grow downwards
  }

  // Smooth shading: area-weighted vertex normals (the unnormalised cross product weighs by area).
  std::vector<Eigen::Vector3d> normal(nv, Eigen::Vector3d::Zero());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d n = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (int c = 0; c < 3; ++c) normal[t[c]] += n;
  }
  for (auto& n : normal) n = n.norm() > 0 ? n.normalized() : toward_camera;

  std::vector<double> depth(static_cast<size_t>(image.width) * image.height, -std::numeric_limits<double>::infinity());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d &a = view[t[0]], &b = view[t[1]], &c = view[t[2]];
    const double area2 = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (std::abs(area2) < 1e-12) continue;  // edge-on or degenerate: covers no pixel centre
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(image.width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(image.height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        // Barycentric coordinates from signed sub-areas; orthographic projection keeps them affine.
        const double w0 = ((b.x() - px) * (c.y() - py) - (b.y() - py) * (c.x() - px)) / area2;
        const double w1 = ((c.x() - px) * (a.y() - py) - (c.y() - py) * (a.x() - px)) / area2;
        const double w2 = 1.0 - w0 - w1;
        // A pixel centre on an edge shared by two triangles can come out a rounding error outside
        // both (w2 is 1 - w0 - w1 in one, a sub-area in the other): a small tolerance keeps it
        // covered, where a strict test left a speck of background in the picture.
        constexpr double kOnEdge = -1e-9;
        if (w0 < kOnEdge || w1 < kOnEdge || w2 < kOnEdge) continue;
        const double z = w0 * a.z() + w1 * b.z() + w2 * c.z();
        const size_t pixel = static_cast<size_t>(y) * image.width + x;
        if (z <= depth[pixel]) continue;
        depth[pixel] = z;
        const Eigen::Vector3d n = (w0 * normal[t[0]] + w1 * normal[t[1]] + w2 * normal[t[2]]).normalized();
        // Two-sided Lambert plus ambient: open meshes show their inside, which must not be black.
        const double shade = 0.3 + 0.7 * std::abs(n.dot(light));
        const auto rgb = surface_colour(t, w0, w1, w2);
        for (int ch = 0; ch < 3; ++ch)
          image.pixels[3 * pixel + ch] = static_cast<std::uint8_t>(std::lround(std::clamp(rgb[ch] * shade, 0.0, 1.0) * 255.0));
      }
    }
  }
  return image;
}

}  // namespace

RgbImage render_preview(const InputMesh& mesh, const InputVertexData<double>& values, const PreviewOptions& options) {
  check_values(mesh, values);
  const double upper_end = options.coloring.upper(values);
  return render_shaded(mesh, options, [&](const std::array<int, 3>& t, double w0, double w1, double w2) {
    const double value = w0 * values[t[0]] + w1 * values[t[1]] + w2 * values[t[2]];
    return color_map_color_float(options.coloring.map, options.coloring.normalise(value, upper_end));
  });
}

std::array<double, 3> species_colour(int species) {
  // Additive on a dark base: distinct hues of similar weight; two species' overlap reads as a pale
  // mix of both. Orange and azure first: told apart also by the common kinds of colour blindness.
  static constexpr std::array<std::array<double, 3>, 8> kPalette = {{{1.00, 0.50, 0.05},
                                                                     {0.10, 0.55, 1.00},
                                                                     {0.35, 0.90, 0.20},
                                                                     {0.95, 0.20, 0.75},
                                                                     {0.95, 0.90, 0.15},
                                                                     {0.15, 0.90, 0.85},
                                                                     {0.60, 0.35, 1.00},
                                                                     {0.90, 0.15, 0.15}}};
  return kPalette[static_cast<size_t>(species) % kPalette.size()];
}

RgbImage render_species_preview(const InputMesh& mesh, const std::vector<InputVertexData<double>>& layers,
                                const std::vector<FieldColoring>& colorings, const PreviewOptions& options) {
  if (layers.empty() || layers.size() != colorings.size())
    throw InputError("species preview of " + mesh.source + ": " + std::to_string(layers.size()) + " layers and " +
                     std::to_string(colorings.size()) + " colourings (one each, at least one)");
  for (const auto& layer : layers) check_values(mesh, layer);
  std::vector<double> upper_end;
  std::vector<std::array<double, 3>> colour;
  for (size_t s = 0; s < layers.size(); ++s) {
    upper_end.push_back(colorings[s].upper(layers[s]));
    colour.push_back(species_colour(static_cast<int>(s)));
  }
  constexpr std::array<double, 3> kBase = {0.06, 0.06, 0.08};  // where no species has pheromone
  return render_shaded(mesh, options, [&](const std::array<int, 3>& t, double w0, double w1, double w2) {
    std::array<double, 3> rgb = kBase;
    for (size_t s = 0; s < layers.size(); ++s) {
      const InputVertexData<double>& u = layers[s];
      const double level = colorings[s].normalise(w0 * u[t[0]] + w1 * u[t[1]] + w2 * u[t[2]], upper_end[s]);
      for (int ch = 0; ch < 3; ++ch) rgb[ch] += level * colour[s][ch];
    }
    for (double& c : rgb) c = std::min(c, 1.0);
    return rgb;
  });
}

RgbImage render_layers_preview(const InputMesh& mesh, const InputVertexData<double>& first, const InputVertexData<double>& last,
                               const InputVertexData<double>& first_share, const LayerColours& colours,
                               const PreviewOptions& options) {
  check_values(mesh, first), check_values(mesh, last), check_values(mesh, first_share);
  return render_shaded(mesh, options, [&](const std::array<int, 3>& t, double w0, double w1, double w2) {
    auto at = [&](const InputVertexData<double>& u) { return w0 * u[t[0]] + w1 * u[t[1]] + w2 * u[t[2]]; };
    return colours.at(at(first), at(last), at(first_share));
  });
}

void write_rgb_png(const std::string& path, const RgbImage& image) {
  write_file_atomically(path, [&](const std::string& temporary) {
    // The format is named explicitly: the temporary file's name does not end in .png.
    auto out = OIIO::ImageOutput::create("png");
    if (!out) throw InputError(path + ": cannot write PNG: " + OIIO::geterror());
    const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    if (!out->open(temporary, spec)) throw InputError(path + ": cannot write PNG: " + out->geterror());
    const bool written = out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data());
    const std::string error = written ? std::string() : out->geterror();
    if (!out->close() || !written) throw InputError(path + ": cannot write PNG: " + (error.empty() ? out->geterror() : error));
  });
}

void write_preview_png(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                       const PreviewOptions& options) {
  write_rgb_png(path, render_preview(mesh, values, options));
}

}  // namespace physarum
