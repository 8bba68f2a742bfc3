// Texture baking onto the input UVs, checked against an independent rasterisation of the UV
// triangles done here: which texels lie in a chart, and the surface point of each. A field linear in
// position must bake to the function at that point: to float precision on a flat mesh (where the
// intrinsic faces are exactly their chord triangles) and within |gradient| x (largest intrinsic
// circumradius) on a curved one (spot.obj), the bound derived in ChordBoundOnSpot. Padding fills
// exactly the margin; UVs wrap; meshes that cannot be baked are refused; the image files read back.
#include "common/base/errors.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/surface/input_face_overlaps.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/output/texture_bake.hpp"
#include "common/output/texture_image.hpp"
#include "test_support.hpp"
#include "uv_test_meshes.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <iostream>

namespace physarum {
namespace {

using testing::TempDir;

// What this test knows about a texel without the code under test: its centre's UV
// ((x + 0.5) / W, 1 - (row + 0.5) / H), how deep inside the best UV triangle it is (the least
// barycentric coordinate there; negative outside every triangle) and its point on the surface.
struct TexelTruth {
  double depth = -HUGE_VAL;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

std::vector<TexelTruth> rasterise_uvs(const InputMesh& mesh, int width, int height) {
  std::vector<TexelTruth> truth(static_cast<size_t>(width) * height);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    std::array<Eigen::Vector2d, 3> uv;
    for (int c = 0; c < 3; ++c) uv[c] = mesh.uvs[mesh.triangle_uvs[t][c]];
    const double area = (uv[1] - uv[0]).x() * (uv[2] - uv[0]).y() - (uv[1] - uv[0]).y() * (uv[2] - uv[0]).x();
    if (std::abs(area) < 1e-300) continue;
    const double u0 = std::min({uv[0].x(), uv[1].x(), uv[2].x()}), u1 = std::max({uv[0].x(), uv[1].x(), uv[2].x()});
    const double v0 = std::min({uv[0].y(), uv[1].y(), uv[2].y()}), v1 = std::max({uv[0].y(), uv[1].y(), uv[2].y()});
    for (int row = std::max(0, int((1.0 - v1) * height) - 2); row <= std::min(height - 1, int((1.0 - v0) * height) + 2); ++row)
      for (int x = std::max(0, int(u0 * width) - 2); x <= std::min(width - 1, int(u1 * width) + 2); ++x) {
        const Eigen::Vector2d p((x + 0.5) / width, 1.0 - (row + 0.5) / height);
        auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
        const double l0 = cross(uv[1] - p, uv[2] - p) / area, l1 = cross(uv[2] - p, uv[0] - p) / area;
        const double l2 = 1.0 - l0 - l1;
        const double depth = std::min({l0, l1, l2});
        TexelTruth& truth_here = truth[static_cast<size_t>(row) * width + x];
        if (depth <= truth_here.depth) continue;
        truth_here.depth = depth;
        const auto& tri = mesh.triangles[t];
        truth_here.point = l0 * mesh.positions[tri[0]] + l1 * mesh.positions[tri[1]] + l2 * mesh.positions[tri[2]];
      }
  }
  return truth;
}

const Eigen::Vector3d kGradient(2.0, -0.5, 3.0);
double linear(const Eigen::Vector3d& p) { return 1.0 + kGradient.dot(p); }

IntrinsicVertexData<double> linear_field(const InputMesh& input, const SurfaceDomain& domain) {
  const FullResolutionMesh full = build_full_resolution_mesh(input, domain);
  IntrinsicVertexData<double> field(full.mesh.positions.size());
  for (size_t v = 0; v < field.size(); ++v) field[v] = linear(full.mesh.positions[v]);
  return field;
}

// The rectangle, simulated at 4x the size (scale_to_area 48 = 16 x 3) and refined: the bake must
// recover the scale, and flips plus insertions give intrinsic faces spanning input faces.
PreparedSurface rectangle_surface() {
  SurfaceSpec spec;
  spec.mesh = "inline uv rectangle";
  spec.scale_to_area = 48.0;
  spec.max_circumradius = 0.6;  // 0.15 in the input's units
  return prepare_surface(testing::make_uv_rectangle(), spec);
}

// Texels whose centre is this deep inside (outside) a UV triangle must (must not) be chart texels;
// closer to an edge either is right.
constexpr double kClearlyInside = 1e-6;

TEST(TextureBake, FlatChartsBakeALinearFieldToFloatPrecision) {
  const PreparedSurface surface = rectangle_surface();
  const int W = 128, H = 96;
  const TexelLocations locations = locate_texels(surface.input, surface.domain, W, H);
  const IntrinsicVertexData<double> field = linear_field(surface.input, surface.domain);
  const BakedTexture texture = bake_fields(locations, surface.domain, {BakeField{"pheromone", field}}, {.margin = 0});
  ASSERT_EQ(texture.width, W);
  ASSERT_EQ(texture.height, H);
  ASSERT_EQ(texture.channels, std::vector<std::string>{"pheromone"});
  const std::vector<TexelTruth> truth = rasterise_uvs(surface.input, W, H);
  // Tolerance: the barycentrics are stored as floats (3 roundings of <= FLT_EPSILON / 2 each, times
  // values up to max |f|) and the result is rounded to float once more: 8 FLT_EPSILON max |f| is ample.
  const double max_f = 1.0 + 2.0 * 3.0 + 0.5 * 1.0;
  const double tolerance = 8.0 * FLT_EPSILON * max_f;
  int charts = 0;
  for (int row = 0; row < H; ++row)
    for (int x = 0; x < W; ++x) {
      const TexelTruth& t = truth[static_cast<size_t>(row) * W + x];
      const TexelCoverage coverage = texture.coverage_at(x, row);
      if (t.depth > kClearlyInside) {
        ASSERT_EQ(coverage, TexelCoverage::Chart) << "texel " << x << ", " << row << " lies in a UV triangle";
        ASSERT_NEAR(texture.value(x, row), linear(t.point), tolerance) << "texel " << x << ", " << row;
        ++charts;
      } else if (t.depth < -kClearlyInside) {
        ASSERT_EQ(coverage, TexelCoverage::Background) << "texel " << x << ", " << row << " is outside every chart";
        ASSERT_EQ(texture.value(x, row), 0.0f);
      }
    }
  // The charts cover 2 x 0.4 x 0.8 of the image.
  EXPECT_NEAR(charts, 0.64 * W * H, 0.02 * W * H);
  EXPECT_EQ(locations.covered_texels, static_cast<size_t>(std::count(texture.coverage.begin(), texture.coverage.end(),
                                                                     TexelCoverage::Chart)));
}

TEST(TextureBake, PaddingFillsExactlyTheMarginAndNeverTouchesCharts) {
  const PreparedSurface surface = rectangle_surface();
  const int W = 96, H = 64, margin = 3;
  const TexelLocations locations = locate_texels(surface.input, surface.domain, W, H);
  const IntrinsicVertexData<double> field = linear_field(surface.input, surface.domain);
  const BakedTexture bare = bake_fields(locations, surface.domain, {BakeField{"f", field}}, {.margin = 0});
  const BakedTexture padded =
      bake_fields(locations, surface.domain, {BakeField{"f", field}}, {.margin = margin, .background = -7.0f});
  int padding = 0, background = 0;
  for (int row = 0; row < H; ++row)
    for (int x = 0; x < W; ++x) {
      if (bare.coverage_at(x, row) == TexelCoverage::Chart) {
        ASSERT_EQ(padded.coverage_at(x, row), TexelCoverage::Chart);
        ASSERT_EQ(padded.value(x, row), bare.value(x, row)) << "padding changed a chart texel";
        continue;
      }
      // Chebyshev distance to the nearest chart texel, wrapping around the edges, by brute force; and
      // the range of chart values within the margin.
      int distance = margin + 1;
      float low = HUGE_VALF, high = -HUGE_VALF;
      for (int dy = -margin; dy <= margin; ++dy)
        for (int dx = -margin; dx <= margin; ++dx) {
          const int nx = (x + dx + W) % W, ny = (row + dy + H) % H;
          if (bare.coverage_at(nx, ny) != TexelCoverage::Chart) continue;
          distance = std::min(distance, std::max(std::abs(dx), std::abs(dy)));
          low = std::min(low, bare.value(nx, ny));
          high = std::max(high, bare.value(nx, ny));
        }
      if (distance <= margin) {
        ASSERT_EQ(padded.coverage_at(x, row), TexelCoverage::Padding) << x << ", " << row << " at distance " << distance;
        // Means of means of chart values: inside their range (float rounding aside).
        ASSERT_GE(padded.value(x, row), low - 1e-5f);
        ASSERT_LE(padded.value(x, row), high + 1e-5f);
        ++padding;
      } else {
        ASSERT_EQ(padded.coverage_at(x, row), TexelCoverage::Background) << x << ", " << row;
        ASSERT_EQ(padded.value(x, row), -7.0f);
        ++background;
      }
    }
  EXPECT_GT(padding, 0);
  EXPECT_GT(background, 0);  // the gap between the charts is wider than twice the margin
}

// Moving every UV by whole tiles changes nothing; moving by half a tile moves the image by half its
// width, the charts crossing u = 1 continuing at the left edge.
TEST(TextureBake, UvsOutsideTheUnitSquareWrap) {
  const PreparedSurface surface = rectangle_surface();
  const int W = 64, H = 48;
  const IntrinsicVertexData<double> field = linear_field(surface.input, surface.domain);
  auto bake_shifted = [&](const Eigen::Vector2d& shift) {
    InputMesh moved = surface.input;
    for (Eigen::Vector2d& uv : moved.uvs) uv += shift;
    return bake_fields(locate_texels(moved, surface.domain, W, H), surface.domain, {BakeField{"f", field}}, {.margin = 0});
  };
  const BakedTexture original = bake_shifted({0.0, 0.0});
  const std::vector<TexelTruth> truth = rasterise_uvs(surface.input, W, H);
  for (const Eigen::Vector2d& shift : {Eigen::Vector2d(1.0, -2.0), Eigen::Vector2d(0.5, 0.0), Eigen::Vector2d(-3.5, 1.0)}) {
    const BakedTexture moved = bake_shifted(shift);
    const int columns = static_cast<int>(std::lround(shift.x() * W));
    int compared = 0;
    for (int row = 0; row < H; ++row)
      for (int x = 0; x < W; ++x) {
        const TexelTruth& t = truth[static_cast<size_t>(row) * W + x];
        if (std::abs(t.depth) < kClearlyInside) continue;  // on an edge: rounding may decide either way
        const int mx = ((x + columns) % W + W) % W;
        ASSERT_EQ(moved.coverage_at(mx, row), original.coverage_at(x, row)) << "shift " << shift.transpose();
        ASSERT_NEAR(moved.value(mx, row), original.value(x, row), 1e-5) << "shift " << shift.transpose();
        ++compared;
      }
    EXPECT_GT(compared, W * H / 2);
  }
}

TEST(TextureBake, RefusesWhatCannotBeBaked) {
  const PreparedSurface surface = rectangle_surface();
  auto message_of = [&](const InputMesh& mesh, int width, int height) {
    try {
      locate_texels(mesh, surface.domain, width, height);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  InputMesh no_uvs = surface.input;
  no_uvs.uvs.clear();
  no_uvs.triangle_uvs.clear();
  EXPECT_NE(message_of(no_uvs, 64, 64).find("has no texture coordinates"), std::string::npos) << message_of(no_uvs, 64, 64);
  InputMesh spanning = surface.input;
  spanning.uvs.push_back(spanning.uvs[static_cast<size_t>(spanning.triangle_uvs[5][1])] + Eigen::Vector2d(1.5, 0.0));
  spanning.triangle_uvs[5][1] = static_cast<int>(spanning.uvs.size()) - 1;  // triangle 5 alone
  EXPECT_NE(message_of(spanning, 64, 64).find("triangle 5 spans more than one texture tile"), std::string::npos)
      << message_of(spanning, 64, 64);
  InputMesh not_finite = surface.input;
  not_finite.uvs[0].y() = std::nan("");
  EXPECT_NE(message_of(not_finite, 64, 64).find("not finite"), std::string::npos);
  InputMesh far_out = surface.input;
  for (Eigen::Vector2d& uv : far_out.uvs) uv.x() += 1e6;
  EXPECT_NE(message_of(far_out, 64, 64).find("tiles from [0, 1]"), std::string::npos) << message_of(far_out, 64, 64);
  EXPECT_NE(message_of(surface.input, 0, 64).find("out of range"), std::string::npos);
  EXPECT_NE(message_of(surface.input, 64, TexelLocations::kMaxSize + 1).find("out of range"), std::string::npos);
  // A real mesh without UVs, as loaded.
  const InputMesh sphere = load_mesh("shape:sphere");
  SurfaceSpec spec;
  spec.mesh = "shape:sphere";
  const PreparedSurface sphere_surface = prepare_surface(sphere, spec);
  EXPECT_THROW(locate_texels(sphere_surface.input, sphere_surface.domain, 16, 16), InputError);
  const IntrinsicVertexData<double> wrong_size{1.0, 2.0};
  const TexelLocations locations = locate_texels(surface.input, surface.domain, 8, 8);
  EXPECT_THROW(bake_fields(locations, surface.domain, {BakeField{"f", wrong_size}}), InputError);
}

// Each intrinsic face is listed under the input faces holding its corners (the flood fill's seeds),
// and the lists cover every point of the surface: here checked on the flat rectangle, where the
// input face under each intrinsic face's centroid is known exactly.
TEST(InputFaceOverlaps, ListsHoldTheFacesUnderEveryIntrinsicFace) {
  const PreparedSurface surface = rectangle_surface();
  const std::vector<ChordTriangle> chords = chord_triangles(surface.input, surface.domain);
  const InputFaceOverlaps overlaps(surface.input, surface.domain, chords);
  EXPECT_NEAR(overlaps.length_scale(), 0.25, 1e-12);  // simulated 4x larger
  auto listed = [&](int input_face, int intrinsic_face) {
    const auto list = overlaps.of(input_face);
    return std::binary_search(list.begin(), list.end(), intrinsic_face);
  };
  const InputMesh& mesh = surface.input;
  for (int f = 0; f < surface.domain.face_count; ++f) {
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(listed(chords[f].input_face[c], f)) << f;
    // Points of the (flat, straight-chorded) intrinsic face: the input faces containing them.
    for (const Eigen::Vector3d& b : {Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3), Eigen::Vector3d(0.8, 0.1, 0.1),
                                     Eigen::Vector3d(0.1, 0.8, 0.1), Eigen::Vector3d(0.1, 0.1, 0.8)}) {
      const Eigen::Vector3d p = b[0] * chords[f].corner[0] + b[1] * chords[f].corner[1] + b[2] * chords[f].corner[2];
      for (int t = 0; t < mesh.triangle_count(); ++t) {
        const auto& tri = mesh.triangles[t];
        const Eigen::Vector3d &a = mesh.positions[tri[0]], &bb = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
        auto side = [&](const Eigen::Vector3d& s, const Eigen::Vector3d& e) { return (e - s).cross(p - s).z(); };
        if (side(a, bb) > 1e-12 && side(bb, c) > 1e-12 && side(c, a) > 1e-12) {
          ASSERT_TRUE(listed(t, f)) << f << " over " << t;
        }
      }
    }
  }
}

// spot.obj, curved: the bound. A texel's surface point x lies in some intrinsic face T, within
// geodesic (hence straight) distance R_T of a corner of T (no point of a triangle is farther than its
// circumradius from its nearest corner), and that corner is on T's chord triangle. The bake picks
// the chord triangle nearest x, or a containing one within 0.05 of its longest edge (<= 0.1 R) of x,
// and a linear field interpolates on a chord triangle to its value at the chosen point y: so
// |baked - f(x)| = |g . (y - x)| <= |g| max(R_T, 0.1 R_C) <= |g| R_max.
TEST(TextureBake, ChordBoundOnSpot) {
  PHYSARUM_REQUIRE_SHARED_MESH(spot, "spot.obj");
  for (const bool refine : {false, true}) {
    SurfaceSpec spec;
    spec.mesh = spot;
    if (refine) spec.max_circumradius = 0.02;
    const PreparedSurface surface = prepare_surface(spec);
    double largest_circumradius = 0.0;
    for (const auto& c : surface.domain.face_corners) {
      const double a = (c[1] - c[0]).norm(), b = (c[2] - c[1]).norm(), d = (c[0] - c[2]).norm();
      const double area = 0.5 * std::abs((c[1] - c[0]).x() * (c[2] - c[0]).y() - (c[1] - c[0]).y() * (c[2] - c[0]).x());
      largest_circumradius = std::max(largest_circumradius, a * b * d / (4.0 * area));
    }
    const int W = 160, H = 160;
    const TexelLocations locations = locate_texels(surface.input, surface.domain, W, H);
    const BakedTexture texture = bake_fields(locations, surface.domain,
                                             {BakeField{"f", linear_field(surface.input, surface.domain)}}, {.margin = 2});
    const std::vector<TexelTruth> truth = rasterise_uvs(surface.input, W, H);
    const double bound = kGradient.norm() * largest_circumradius + 1e-5;
    double worst = 0.0, sum = 0.0;
    int charts = 0;
    for (int row = 0; row < H; ++row)
      for (int x = 0; x < W; ++x) {
        const TexelTruth& t = truth[static_cast<size_t>(row) * W + x];
        if (t.depth <= kClearlyInside) continue;
        ASSERT_EQ(texture.coverage_at(x, row), TexelCoverage::Chart) << x << ", " << row;
        const double error = std::abs(texture.value(x, row) - linear(t.point));
        ASSERT_LE(error, bound) << "texel " << x << ", " << row << (refine ? " (refined)" : "");
        worst = std::max(worst, error);
        sum += error;
        ++charts;
      }
    ASSERT_GT(charts, W * H / 4);
    std::cout << "spot " << surface.domain.face_count << " intrinsic faces, R_max " << largest_circumradius
              << ": bake error mean " << sum / charts << ", worst " << worst << " (bound " << bound << "); "
              << locations.nearest_search_texels << " of " << locations.covered_texels << " texels searched\n";
  }
}

template <typename T>
std::vector<T> read_image(const std::string& path, OIIO::TypeDesc type, OIIO::ImageSpec& spec) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return {};
  spec = in->spec();
  std::vector<T> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, type, pixels.data()));
  in->close();
  return pixels;
}

TEST(TextureFiles, PngAndExrReadBackWithTheBakedValues) {
  const PreparedSurface surface = rectangle_surface();
  const int W = 80, H = 60;
  const IntrinsicVertexData<double> field = linear_field(surface.input, surface.domain);
  const BakedTexture texture = bake_fields(locate_texels(surface.input, surface.domain, W, H), surface.domain,
                                           {BakeField{"pheromone", field}}, {.margin = 2});
  TextureColouring colouring;
  colouring.upper_end = 8.0;
  colouring.background = {10, 20, 30};
  TempDir dir;
  const std::string png8 = (dir.path / "texture.png").string(), png16 = (dir.path / "texture16.png").string(),
                    exr = (dir.path / "texture.exr").string();
  write_texture_png(png8, texture, 0, colouring, 8);
  write_texture_png(png16, texture, 0, colouring, 16);
  write_texture_exr(exr, texture);
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir.path)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"texture.exr", "texture.png", "texture16.png"})) << "temporary files left";

  OIIO::ImageSpec spec8, spec16, spec_exr;
  const auto bytes = read_image<std::uint8_t>(png8, OIIO::TypeDesc::UINT8, spec8);
  const auto words = read_image<std::uint16_t>(png16, OIIO::TypeDesc::UINT16, spec16);
  const auto floats = read_image<float>(exr, OIIO::TypeDesc::FLOAT, spec_exr);
  ASSERT_EQ(spec8.width, W);
  ASSERT_EQ(spec8.height, H);
  ASSERT_EQ(spec8.nchannels, 3);
  EXPECT_EQ(spec8.format, OIIO::TypeDesc::UINT8);
  ASSERT_EQ(spec16.nchannels, 3);
  EXPECT_EQ(spec16.format, OIIO::TypeDesc::UINT16);
  ASSERT_EQ(spec_exr.width, W);
  ASSERT_EQ(spec_exr.nchannels, 1);
  EXPECT_EQ(spec_exr.channelnames, std::vector<std::string>{"pheromone"});
  EXPECT_EQ(spec_exr.format, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(texture_rgb8(texture, 0, colouring), bytes) << "the pixels for embedding are texture.png's";
  for (int row = 0; row < H; ++row)
    for (int x = 0; x < W; ++x) {
      const size_t p = static_cast<size_t>(row) * W + x;
      ASSERT_EQ(floats[p], texture.value(x, row));
      if (texture.coverage_at(x, row) == TexelCoverage::Background) {
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(bytes[3 * p + c], colouring.background[c]);
          ASSERT_EQ(words[3 * p + c], colouring.background[c] * 257);
        }
        continue;
      }
      // The PLY's colour rule: viridis over 0 .. upper_end, rounded to the file's depth.
      const double t = std::clamp(texture.value(x, row) / 8.0, 0.0, 1.0);
      const Rgb8 expected8 = color_map_color(ColorMap::viridis(), t);
      const auto expected = color_map_color_float(ColorMap::viridis(), t);
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(bytes[3 * p + c], expected8[c]) << x << ", " << row;
        ASSERT_EQ(words[3 * p + c], std::lround(expected[c] * 65535.0)) << x << ", " << row;
      }
    }
  // A folder that does not exist: an error naming the file, and nothing written.
  const std::string missing = (dir.path / "none" / "texture.png").string();
  EXPECT_THROW(write_texture_png(missing, texture, 0, colouring), InputError);
  EXPECT_THROW(write_texture_exr((dir.path / "none" / "texture.exr").string(), texture), InputError);
  EXPECT_THROW(write_texture_png(png8, texture, 1, colouring), InputError);  // no such channel
}

}  // namespace
}  // namespace physarum
