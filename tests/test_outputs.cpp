// Result outputs: the PLY file (parsed back here byte by byte),
// the preview PNG (read back through OpenImageIO), the colour maps, and atomic writes that leave no
// partial file behind.
#include "common/base/atomic_write.hpp"
#include "common/color/color_map.hpp"
#include "common/base/errors.hpp"
#include "common/output/ply_writer.hpp"
#include "common/output/preview_image.hpp"
#include "pheromone_test_meshes.hpp"
#include "ply_layout_parser.hpp"
#include "test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <random>
#include <sstream>

namespace physarum {
namespace {

using testing::parse_ply;
using testing::ParsedPly;
using testing::TempDir;

InputVertexData<double> linear_field(const InputMesh& mesh) {
  InputVertexData<double> f(mesh.positions.size());
  for (size_t v = 0; v < f.size(); ++v) f[v] = 1.0 + 2.0 * mesh.positions[v].x() - 0.5 * mesh.positions[v].y() + 3.0 * mesh.positions[v].z();
  return f;
}

std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

// ---- colour maps ---------------------------------------------------------------------------------

// Perceptual maps: relative luminance rises strictly from 0 to 1, and the ends are the maps' known
// end colours (viridis dark purple #440154 -> yellow #FDE725, magma black -> pale yellow).
TEST(ColorMap, LuminanceRisesMonotonically) {
  for (const ColorMap& map : {ColorMap::named("viridis"), ColorMap::named("magma"), ColorMap::named("inferno")}) {
    double previous = -1.0;
    for (int k = 0; k <= 100; ++k) {
      const auto c = color_map_color_float(map, k / 100.0);
      const double luminance = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
      ASSERT_GT(luminance, previous) << "t = " << k / 100.0;
      previous = luminance;
    }
  }
  EXPECT_EQ(color_map_color(ColorMap::viridis(), 0.0), (Rgb8{0x44, 0x01, 0x54}));
  EXPECT_EQ(color_map_color(ColorMap::viridis(), 1.0), (Rgb8{0xFD, 0xE7, 0x25}));
  EXPECT_EQ(color_map_color(ColorMap::viridis(), 7.0), color_map_color(ColorMap::viridis(), 1.0));  // clamped
  EXPECT_EQ(color_map_color(ColorMap::named("magma"), 0.0), (Rgb8{0x00, 0x00, 0x04}));
}

// ---- PLY -----------------------------------------------------------------------------------------

TEST(PlyWriter, RoundTripKeepsInputMeshAndValues) {
  const InputMesh mesh = testing::make_icosphere(2);
  const InputVertexData<double> values = linear_field(mesh);
  TempDir dir;
  const std::string path = (dir.path / "pheromone.ply").string();
  write_field_ply(path, mesh, values);
  const ParsedPly ply = parse_ply(path);
  ASSERT_GE(ply.header.size(), 3u);
  EXPECT_EQ(ply.header[0], "ply");
  EXPECT_EQ(ply.header[1], "format binary_little_endian 1.0");
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "property float pheromone"), ply.header.end());
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "property uchar red"), ply.header.end());
  ASSERT_EQ(ply.vertices, mesh.vertex_count());
  ASSERT_EQ(ply.faces, mesh.triangle_count());
  const std::vector<float> pheromone = ply.property("pheromone");
  ASSERT_EQ(pheromone.size(), values.size());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) ASSERT_EQ(ply.vertex[v][c], static_cast<float>(mesh.positions[v][c]));
    ASSERT_EQ(pheromone[v], static_cast<float>(values[v]));
  }
  for (int f = 0; f < mesh.triangle_count(); ++f) ASSERT_EQ(ply.face[f], mesh.triangles[f]);
  // Colours span the map: the largest value gets the top colour, the smallest one near the bottom.
  const auto top = std::max_element(values.begin(), values.end()) - values.begin();
  EXPECT_EQ(ply.color[top], color_map_color(ColorMap::viridis(), 1.0));
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"pheromone.ply"}) << "temporary file left behind";
}

TEST(PlyWriter, SizeMismatchThrowsAndWritesNothing) {
  const InputMesh mesh = testing::make_square_grid(2);
  TempDir dir;
  EXPECT_THROW(write_field_ply((dir.path / "p.ply").string(), mesh, InputVertexData<double>{1.0, 2.0}), InputError);
  EXPECT_TRUE(files_in(dir.path).empty());
}

// ---- atomic writes -------------------------------------------------------------------------------

TEST(AtomicWrite, FailingWriteLeavesNoFile) {
  const InputMesh mesh = testing::make_square_grid(2);
  const InputVertexData<double> values(static_cast<size_t>(mesh.vertex_count()), 1.0);
  TempDir dir;
  // A folder that does not exist, and a "folder" that is a regular file.
  const std::string missing = (dir.path / "no-such-dir" / "pheromone.ply").string();
  std::ofstream(dir.path / "plain-file") << "x";
  const std::string under_file = (dir.path / "plain-file" / "preview.png").string();
  EXPECT_THROW(write_field_ply(missing, mesh, values), InputError);
  EXPECT_THROW(write_preview_png(under_file, mesh, values), InputError);
  EXPECT_THROW(write_text_file_atomically(missing, "x"), InputError);
  try {
    write_field_ply(missing, mesh, values);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"plain-file"});

  // A writer that fails half-way: the temporary file it started is removed and an existing file at
  // the target keeps its old content.
  const std::string target = (dir.path / "stats.csv").string();
  write_text_file_atomically(target, "old\n");
  std::string temporary_seen;
  EXPECT_THROW(write_file_atomically(target,
                                     [&](const std::string& temporary) {
                                       temporary_seen = temporary;
                                       std::ofstream(temporary) << "half";
                                       throw std::runtime_error("disk full");
                                     }),
               InputError);
  EXPECT_FALSE(temporary_seen.empty());
  EXPECT_NE(temporary_seen, target);
  EXPECT_FALSE(std::filesystem::exists(temporary_seen));
  // The same when the writer reports its own InputError (passed through unchanged).
  temporary_seen.clear();
  try {
    write_file_atomically(target, [&](const std::string& temporary) {
      temporary_seen = temporary;
      std::ofstream(temporary) << "half";
      throw InputError("writer: encoder failed");
    });
    FAIL() << "the writer's error was swallowed";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "writer: encoder failed");
  }
  EXPECT_FALSE(std::filesystem::exists(temporary_seen));
  EXPECT_EQ(files_in(dir.path).size(), 2u);  // plain-file and stats.csv only
  std::ifstream in(target);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), "old\n");
}

// ---- preview -------------------------------------------------------------------------------------

struct ReadImage {
  int width = 0, height = 0, channels = 0;
  std::vector<unsigned char> pixels;
};

ReadImage read_png(const std::string& path) {
  ReadImage image;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return image;
  const OIIO::ImageSpec& spec = in->spec();
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.pixels.resize(static_cast<size_t>(image.width) * image.height * image.channels);
  in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::UINT8, image.pixels.data());
  in->close();
  return image;
}

TEST(PreviewImage, WritesShadedPngOfRequestedSize) {
  const InputMesh mesh = testing::make_icosphere(3);
  TempDir dir;
  const std::string path = (dir.path / "preview.png").string();
  // Hot near +z, cold elsewhere.
  InputVertexData<double> values(mesh.positions.size());
  for (size_t v = 0; v < values.size(); ++v) values[v] = std::max(0.0, mesh.positions[v].z());
  write_preview_png(path, mesh, values);
  const ReadImage image = read_png(path);
  ASSERT_EQ(image.width, 800);
  ASSERT_EQ(image.height, 600);
  ASSERT_EQ(image.channels, 3);
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"preview.png"}) << "temporary file left behind";

  // Not uniform: background, and both ends of the colour map appear.
  size_t background = 0, distinct_from_corner = 0;
  for (size_t p = 0; p < image.pixels.size(); p += 3) {
    const bool is_background = image.pixels[p] == 255 && image.pixels[p + 1] == 255 && image.pixels[p + 2] == 255;
    background += is_background;
    distinct_from_corner += !is_background;
  }
  const size_t total = image.pixels.size() / 3;
  EXPECT_GT(background, total / 10);            // margin around the fitted sphere
  EXPECT_GT(distinct_from_corner, total / 4);   // the sphere fills a good part of the frame
  // The sphere is centred: the centre pixel is surface, the corner pixel is background.
  const size_t centre = (300 * 800 + 400) * 3;
  EXPECT_FALSE(image.pixels[centre] == 255 && image.pixels[centre + 1] == 255 && image.pixels[centre + 2] == 255);
  EXPECT_EQ(image.pixels[0], 255);

  // The hot cap (+z faces the camera at azimuth 35 deg) is yellow-green, the cold side purple-blue:
  // some pixel is much greener than blue and some much bluer than green.
  bool warm = false, cold = false;
  for (size_t p = 0; p < image.pixels.size(); p += 3) {
    const int g = image.pixels[p + 1], b = image.pixels[p + 2];
    if (image.pixels[p] == 255 && g == 255 && b == 255) continue;
    warm |= g > b + 60;
    cold |= b > g + 30;
  }
  EXPECT_TRUE(warm);
  EXPECT_TRUE(cold);
}

// Hidden surfaces stay hidden: a field hot only on the far side of the sphere must not show any
// hot colour (without a depth test, far triangles drawn later would paint over near ones).
TEST(PreviewImage, DepthTestHidesTheFarSide) {
  const InputMesh mesh = testing::make_icosphere(3);
  PreviewOptions options;
  options.width = 200;
  options.height = 150;
  const double az = options.azimuth_deg * std::numbers::pi / 180, el = options.elevation_deg * std::numbers::pi / 180;
  const Eigen::Vector3d toward_camera(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  InputVertexData<double> values(mesh.positions.size());
  for (size_t v = 0; v < values.size(); ++v) values[v] = mesh.positions[v].dot(toward_camera) < -0.3 ? 1.0 : 0.0;
  ASSERT_GT(*std::max_element(values.begin(), values.end()), 0.0);
  const RgbImage image = render_preview(mesh, values, options);
  const Rgb8 hot = color_map_color(ColorMap::viridis(), 1.0);
  for (size_t p = 0; p < image.pixels.size(); p += 3) {
    const int g = image.pixels[p + 1], b = image.pixels[p + 2];
    if (image.pixels[p] == 255 && g == 255 && b == 255) continue;
    ASSERT_LT(g, b + 40) << "a far-side (hot) colour shows through at pixel " << p / 3 << "; hot = " << int(hot[1]);
  }
}

TEST(PreviewImage, HonoursSizeOptionAndRejectsBadSize) {
  const InputMesh mesh = testing::make_square_grid(4);
  const InputVertexData<double> values = linear_field(mesh);
  PreviewOptions options;
  options.width = 160;
  options.height = 90;
  const RgbImage image = render_preview(mesh, values, options);
  EXPECT_EQ(image.width, 160);
  EXPECT_EQ(image.height, 90);
  EXPECT_EQ(image.pixels.size(), 160u * 90u * 3u);
  options.width = 0;
  EXPECT_THROW(render_preview(mesh, values, options), InputError);
  EXPECT_THROW(render_preview(mesh, InputVertexData<double>{1.0}, PreviewOptions{}), InputError);
}

}  // namespace
}  // namespace physarum
