// `physarum render` as a user runs it on a finished run: the values come back unchanged, the colours
// are the requested map over the run's 0..2U range, every requested view is drawn at the requested
// size, and a folder that is not a run writes nothing.
#include "common/color/color_map.hpp"
#include "common/mesh/ply_reader.hpp"
#include "test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;

// A short reference run on a small square (seconds), shared by the tests below.
class RenderCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    std::ofstream(dir_->path / "scene.json") << R"({
  "mesh": "shape:square", "scale_to_area": 1.0, "agents": 1000, "time_step": 0.02,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward", "seed": 3
})";
    run_ = run_physarum("run " + quoted(dir_->path / "scene.json") + " --backend reference --steps 30 --out " +
                        quoted(dir_->path / "run"));
  }
  static void TearDownTestSuite() { delete dir_; }
  static fs::path run_dir() { return dir_->path / "run"; }
  static inline TempDir* dir_ = nullptr;
  static inline CommandResult run_;
};

std::array<int, 3> image_shape(const fs::path& p) {
  auto in = OIIO::ImageInput::open(p.string());
  if (!in) return {0, 0, 0};
  const OIIO::ImageSpec& s = in->spec();
  return {s.width, s.height, s.nchannels};
}

TEST_F(RenderCommand, RecoloursWithoutChangingValues) {
  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  const fs::path out = dir_->path / "magma";
  const CommandResult r = run_physarum("render " + quoted(run_dir()) + " --colormap magma --views 3 --width 320 --height 240 --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  std::ifstream run_json(run_dir() / "run.json");
  const double U = nlohmann::json::parse(run_json)["U"].get<double>();
  const PlyFields before = read_ply_fields((run_dir() / "pheromone.ply").string());
  const PlyFields after = read_ply_fields((out / "pheromone.ply").string());
  ASSERT_EQ(after.mesh.triangles, before.mesh.triangles);
  ASSERT_EQ(after.property("pheromone"), before.property("pheromone"));
  // Colours: magma at value / 2U (clamped), the range `physarum run` uses.
  const auto& values = after.property("pheromone");
  for (size_t v = 0; v < values.size(); ++v) {
    const Rgb8 expected = color_map_color(ColorMap::named("magma"), values[v] / (2.0 * U));
    ASSERT_EQ(after.property("red")[v], expected[0]) << "vertex " << v;
    ASSERT_EQ(after.property("green")[v], expected[1]) << "vertex " << v;
    ASSERT_EQ(after.property("blue")[v], expected[2]) << "vertex " << v;
  }
  for (const char* name : {"preview.png", "view_front.png", "view_side.png", "view_top.png"})
    EXPECT_EQ(image_shape(out / name), (std::array<int, 3>{320, 240, 3})) << name;
}

// A reaction-diffusion run: the pictures show its preview morphogen, coloured over 0 .. twice the
// run's color_unit (half the preview morphogen's largest value, so its maximum sits at the top of
// the map), and the recoloured PLY keeps every morphogen's values.
TEST(RenderReactionDiffusion, RecoloursThePreviewMorphogenAndKeepsEveryMorphogen) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << R"({"mesh": "shape:square", "scale_to_area": 1.0, "model": "gray-scott",
    "initial": {"noise": 0.01, "spots": {"count": 3, "radius": 0.1, "values": {"u": 0.5, "v": 0.25}}},
    "time_step": 1.0, "seed": 2})";
  const CommandResult run = run_physarum("run " + quoted(dir.path / "scene.json") + " --backend reference --steps 40 --out " +
                                         quoted(dir.path / "run"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const fs::path out = dir.path / "magma";
  const CommandResult r = run_physarum("render " + quoted(dir.path / "run") + " --colormap magma --views 1 --width 64 --height 48 --out " +
                                       quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream run_json(dir.path / "run" / "run.json");
  const double unit = nlohmann::json::parse(run_json)["color_unit"].get<double>();
  // A reaction-diffusion run's result on the input mesh is named for what it holds.
  EXPECT_FALSE(fs::exists(dir.path / "run" / "pheromone.ply"));
  const PlyFields before = read_ply_fields((dir.path / "run" / "morphogens.ply").string());
  const PlyFields after = read_ply_fields((out / "morphogens.ply").string());
  ASSERT_EQ(after.property("u"), before.property("u"));
  ASSERT_EQ(after.property("v"), before.property("v"));
  const auto& v = after.property("v");
  EXPECT_NEAR(*std::max_element(v.begin(), v.end()), 2.0 * unit, 1e-6 * unit);
  for (size_t i = 0; i < v.size(); ++i) {
    const Rgb8 expected = color_map_color(ColorMap::named("magma"), v[i] / (2.0 * unit));
    ASSERT_EQ(after.property("red")[i], expected[0]) << "vertex " << i;
  }
  EXPECT_EQ(image_shape(out / "preview.png"), (std::array<int, 3>{64, 48, 3}));
}

TEST_F(RenderCommand, TurntableDrawsDistinctFrames) {
  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  const fs::path out = dir_->path / "turntable";
  const CommandResult r = run_physarum("render " + quoted(run_dir()) + " --views 4 --width 64 --height 48 --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> frames;
  for (int k = 0; k < 4; ++k) {
    const fs::path frame = out / ("view_turntable_00" + std::to_string(k) + ".png");
    ASSERT_TRUE(fs::exists(frame)) << frame;
    std::ifstream in(frame, std::ios::binary);
    frames.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // A square seen from four sides a quarter turn apart: no two frames are the same picture.
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) EXPECT_NE(frames[a], frames[b]) << a << " vs " << b;
}

TEST_F(RenderCommand, BadRunFolderWritesNothing) {
  TempDir empty;
  const fs::path out = empty.path / "render";
  const CommandResult r = run_physarum("render " + quoted(empty.path) + " --out " + quoted(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("run.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));

  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  EXPECT_EQ(run_physarum("render " + quoted(run_dir()) + " --views 0 --out " + quoted(out)).exit_code, 2);
  EXPECT_EQ(run_physarum("render " + quoted(run_dir()) + " --colormap no-such-map --out " + quoted(out)).exit_code, 2);
  EXPECT_FALSE(fs::exists(out));
}

// A square with UVs over the whole texture, so every texel lies on the surface.
constexpr const char* kUvSquareObj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1 2/2 3/3
f 1/1 3/3 4/4
)";

// A run on a mesh with UVs bakes texture.png; render bakes it again in the new colours.
class RenderTexture : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    std::ofstream(dir_->path / "square.obj") << kUvSquareObj;
    std::ofstream(dir_->path / "scene.json") << R"({
  "mesh": "square.obj", "scale_to_area": 1.0, "max_circumradius": 0.04, "agents": 1000, "time_step": 0.02,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward", "seed": 5
})";
    run_ = run_physarum("run " + quoted(dir_->path / "scene.json") +
                        " --backend reference --steps 30 --texture-size 48 --texture-format exr --out " +
                        quoted(dir_->path / "run"));
  }
  static void TearDownTestSuite() { delete dir_; }
  static fs::path run_dir() { return dir_->path / "run"; }
  static inline TempDir* dir_ = nullptr;
  static inline CommandResult run_;
};

std::vector<float> read_pixels(const fs::path& p, int expected_channels) {
  auto in = OIIO::ImageInput::open(p.string());
  if (!in || in->spec().nchannels != expected_channels) return {};
  std::vector<float> pixels(static_cast<size_t>(in->spec().width) * in->spec().height * expected_channels);
  return in->read_image(0, 0, 0, expected_channels, OIIO::TypeDesc::FLOAT, pixels.data()) ? pixels
                                                                                           : std::vector<float>{};
}

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The largest difference between two 8-bit images, in levels (read back as 0..1 floats).
double max_level_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(static_cast<double>(a[i]) - b[i]) * 255.0);
  return worst;
}

TEST_F(RenderTexture, RebakesTextureAndGlbInTheNewColours) {
  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  const std::vector<float> run_texture = read_pixels(run_dir() / "texture.png", 3);
  const std::vector<float> raw = read_pixels(run_dir() / "texture.exr", 1);
  ASSERT_EQ(run_texture.size(), 48u * 48u * 3u);
  ASSERT_EQ(raw.size(), 48u * 48u);

  // The run's own colours: the same texture (the values come back from fields_full.ply as floats,
  // so a texel on a colour step may move by one level).
  const fs::path same = dir_->path / "same";
  CommandResult r = run_physarum("render " + quoted(run_dir()) + " --views 1 --width 32 --height 24 --out " + quoted(same));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LE(max_level_difference(read_pixels(same / "texture.png", 3), run_texture), 1.0);
  EXPECT_TRUE(fs::exists(same / "texture.exr"));  // the run's format is kept

  // magma: every texel is magma at its raw value / 2U, the range `physarum run` colours over.
  std::ifstream run_json(run_dir() / "run.json");
  const double U = nlohmann::json::parse(run_json)["U"].get<double>();
  const fs::path magma = dir_->path / "magma";
  r = run_physarum("render " + quoted(run_dir()) + " --colormap magma --views 1 --width 32 --height 24 --out " + quoted(magma));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<float> recoloured = read_pixels(magma / "texture.png", 3);
  ASSERT_EQ(recoloured.size(), run_texture.size());
  EXPECT_GT(max_level_difference(recoloured, run_texture), 50.0);
  std::vector<float> expected(recoloured.size());
  for (size_t t = 0; t < raw.size(); ++t) {
    const Rgb8 c = color_map_color(ColorMap::named("magma"), raw[t] / (2.0 * U));
    for (size_t k = 0; k < 3; ++k) expected[3 * t + k] = static_cast<float>(c[k] / 255.0);
  }
  EXPECT_LE(max_level_difference(recoloured, expected), 1.0);

  // result.glb embeds that texture: its PNG (after the JSON chunk) decodes to the same pixels.
  const std::string glb = file_bytes(magma / "result.glb");
  EXPECT_NE(glb, file_bytes(run_dir() / "result.glb"));
  const size_t png_at = glb.find("\x89PNG\r\n\x1a\n");
  ASSERT_NE(png_at, std::string::npos);
  TempDir extracted;
  std::ofstream(extracted.path / "embedded.png", std::ios::binary) << glb.substr(png_at);
  EXPECT_EQ(read_pixels(extracted.path / "embedded.png", 3), recoloured);
}

// A texture needs the surface the run simulated on: a mesh file changed since then is refused,
// naming it, and nothing is written.
TEST_F(RenderTexture, ChangedMeshIsRefused) {
  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  TempDir copy;
  fs::copy(run_dir(), copy.path / "run");
  const std::string moved = std::string(kUvSquareObj).replace(0, 7, "v 0 0 0.3");
  std::ofstream(dir_->path / "square.obj") << moved;
  const fs::path out = copy.path / "render";
  const CommandResult r = run_physarum("render " + quoted(copy.path / "run") + " --out " + quoted(out));
  std::ofstream(dir_->path / "square.obj") << kUvSquareObj;  // restore for the other tests
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("square.obj"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace physarum::testing
