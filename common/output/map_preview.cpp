#include "common/output/map_preview.hpp"

#include "common/output/color_map_strip.hpp"
#include "common/base/errors.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>

namespace physarum {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr const char* kFont = "DejaVuSans";
constexpr int kStrokeCellsAcross = 30;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

void check_size(const MapPreviewOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    throw InputError("map preview: image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                     " is out of range (1..16384 each)");
}

int band_height(const MapPreviewOptions& o) { return o.height >= 2 * kMapPreviewBand ? kMapPreviewBand : 0; }

PreviewOptions view_options(const MapPreviewOptions& o, const FieldColoring& coloring) {
  PreviewOptions p;
  p.width = o.width;
  p.height = o.height - band_height(o);
  p.coloring = coloring;
  p.azimuth_deg = o.azimuth_deg;
  p.elevation_deg = o.elevation_deg;
  return p;
}

// The picture with a white band of `band` rows added underneath.
RgbImage with_band(const RgbImage& view, int band) {
  RgbImage out;
  out.width = view.width;
  out.height = view.height + band;
  out.pixels.assign(static_cast<size_t>(out.width) * out.height * 3, 255);
  std::copy(view.pixels.begin(), view.pixels.end(), out.pixels.begin());
  return out;
}

void text(RgbImage& image, int x, int y, const std::string& s, OIIO::ImageBufAlgo::TextAlignX align) {
  OIIO::ImageBuf buffer(OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::UINT8), image.pixels.data());
  const float ink[3] = {0.1f, 0.1f, 0.1f};
  // Without the font the band stays unlabelled; the picture is still useful.
  OIIO::ImageBufAlgo::render_text(buffer, x, y, s, 14, kFont, ink, align, OIIO::ImageBufAlgo::TextAlignY::Baseline);
}

}  // namespace

RgbImage render_scalar_map_preview(const InputMesh& mesh, const InputVertexData<double>& values, const std::string& name,
                                   const MapPreviewOptions& options) {
  check_size(options);
  if (static_cast<int>(values.size()) != mesh.vertex_count())
    throw InputError("map preview of '" + name + "': " + std::to_string(values.size()) + " values for " +
                     std::to_string(mesh.vertex_count()) + " vertices");
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const double v : values) low = std::min(low, v), high = std::max(high, v);
  if (values.empty()) low = high = 0.0;
  FieldColoring coloring;  // viridis over min .. max
  coloring.low = low;
  coloring.high = high;
  const int band = band_height(options);
  RgbImage image = with_band(render_preview(mesh, values, view_options(options, coloring)), band);
  if (band == 0) return image;

  // The strip: the colour map from the minimum (left) to the maximum (right).
  const int margin = std::min(70, image.width / 4);
  const int strip_width = image.width - 2 * margin;
  const int strip_top = image.height - band + 8;
  if (strip_width >= 2) {
    const RgbImage strip = color_map_strip(coloring.map, strip_width, 14);
    for (int y = 0; y < strip.height; ++y)
      std::copy_n(strip.pixels.begin() + static_cast<long>(y) * strip.width * 3, strip.width * 3,
                  image.pixels.begin() + (static_cast<long>(strip_top + y) * image.width + margin) * 3);
  }
  using AX = OIIO::ImageBufAlgo::TextAlignX;
  const int baseline = strip_top + 14 + 20;
  text(image, margin, baseline, number(low), AX::Left);
  text(image, image.width - margin, baseline, number(high), AX::Right);
  text(image, image.width / 2, baseline, name + (high > low ? std::string() : " (constant)"), AX::Center);
  return image;
}

RgbImage render_vector_map_preview(const InputMesh& input, const std::vector<Eigen::Vector3d>& vectors,
                                   const std::string& name, const MapPreviewOptions& options) {
  check_size(options);
  if (static_cast<int>(vectors.size()) != input.triangle_count())
    throw InputError("map preview of '" + name + "': " + std::to_string(vectors.size()) + " vectors for " +
                     std::to_string(input.triangle_count()) + " triangles");

  // One arrow per grid cell: the face whose centroid is nearest the cell's centre.
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const Vec3& p : input.positions) low = low.cwiseMin(p), high = high.cwiseMax(p);
  const double diagonal = input.positions.empty() ? 0.0 : (high - low).norm();
  const double cell = diagonal > 0 ? diagonal / kStrokeCellsAcross : 1.0;
  double longest = 0.0;
  for (const Vec3& v : vectors) longest = std::max(longest, v.norm());
  std::map<std::tuple<long, long, long>, std::pair<double, int>> chosen;  // cell -> (distance, face)
  for (int f = 0; f < input.triangle_count() && longest > 0; ++f) {
    if (!(vectors[static_cast<size_t>(f)].norm() > 0)) continue;
    const auto& t = input.triangles[static_cast<size_t>(f)];
    const Vec3 centroid = (input.positions[t[0]] + input.positions[t[1]] + input.positions[t[2]]) / 3.0;
    const Eigen::Array3d index = ((centroid - low) / cell).array().floor();
    const Vec3 centre = low + cell * (index + 0.5).matrix();
    const auto key = std::make_tuple(static_cast<long>(index[0]), static_cast<long>(index[1]), static_cast<long>(index[2]));
    const double distance = (centroid - centre).norm();
    auto [it, fresh] = chosen.emplace(key, std::make_pair(distance, f));
    if (!fresh && distance < it->second.first) it->second = {distance, f};
  }

  // The surface (value 0, grey) and the arrows (value 1, dark red) in one mesh for the renderer.
  InputMesh scene = input;
  scene.uvs.clear();
  scene.triangle_uvs.clear();
  InputVertexData<double> values(static_cast<size_t>(input.vertex_count()), 0.0);
  auto add_triangle = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const int first = static_cast<int>(scene.positions.size());
    for (const Vec3* p : {&a, &b, &c}) {
      scene.positions.push_back(*p);
      values.values().push_back(1.0);
    }
    scene.triangles.push_back({first, first + 1, first + 2});
  };
  const double lift = 2e-3 * diagonal;  // above the face, against depth fighting
  for (const auto& [key, pick] : chosen) {
    const int f = pick.second;
    const auto& t = input.triangles[static_cast<size_t>(f)];
    const Vec3 &a = input.positions[t[0]], &b = input.positions[t[1]], &c = input.positions[t[2]];
    const Vec3 normal = (b - a).cross(c - a);
    if (!(normal.norm() > 0)) continue;
    const Vec3 n = normal.normalized();
    const Vec3& v = vectors[static_cast<size_t>(f)];
    const double length = 0.8 * cell * v.norm() / longest;
    if (length < 0.05 * cell) continue;  // too short to show a direction
    const Vec3 along = v.normalized(), across = n.cross(along);
    const Vec3 centroid = (a + b + c) / 3.0;
    const double shaft = 0.05 * cell, head = 0.16 * cell, head_length = std::min(0.35 * length, 0.3 * cell);
    for (const double side : {1.0, -1.0}) {  // on both sides: the far side of an open surface shows too
      const Vec3 base = centroid + side * lift * n;
      const Vec3 tail = base - 0.5 * length * along, tip = base + 0.5 * length * along, neck = tip - head_length * along;
      add_triangle(tail - shaft * across, neck - shaft * across, neck + shaft * across);
      add_triangle(tail - shaft * across, neck + shaft * across, tail + shaft * across);
      add_triangle(neck - head * across, tip, neck + head * across);
    }
  }
  const SrgbColor grey = {0.82, 0.82, 0.80}, ink = {0.70, 0.08, 0.08};
  FieldColoring coloring;
  coloring.map = ColorMap("surface-and-arrows", {{0.0, grey}, {0.5, grey}, {0.5, ink}, {1.0, ink}});
  coloring.low = 0.0;
  coloring.high = 1.0;
  const int band = band_height(options);
  RgbImage image = with_band(render_preview(scene, values, view_options(options, coloring)), band);
  if (band == 0) return image;
  double shortest = std::numeric_limits<double>::infinity();
  for (const Vec3& v : vectors) shortest = std::min(shortest, v.norm());
  if (vectors.empty()) shortest = 0.0;
  using AX = OIIO::ImageBufAlgo::TextAlignX;
  text(image, image.width / 2, image.height - band + 34,
       name + ": vector map, |v| from " + number(shortest) + " to " + number(longest) + " (arrow length ~ |v|)", AX::Center);
  return image;
}

}  // namespace physarum
