// `physarum render` as a user runs it on a finished run: the values come back unchanged, the colours
// are the requested map over the run's 0..2U range, every requested view is drawn at the requested
// size, and a folder that is not a run writes nothing.
#include "common/colormap.hpp"
#include "common/ply_reader.hpp"
#include "test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

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
    const Rgb8 expected = colormap_color(ColorMap::named("magma"), values[v] / (2.0 * U));
    ASSERT_EQ(after.property("red")[v], expected[0]) << "vertex " << v;
    ASSERT_EQ(after.property("green")[v], expected[1]) << "vertex " << v;
    ASSERT_EQ(after.property("blue")[v], expected[2]) << "vertex " << v;
  }
  for (const char* name : {"preview.png", "view_front.png", "view_side.png", "view_top.png"})
    EXPECT_EQ(image_shape(out / name), (std::array<int, 3>{320, 240, 3})) << name;
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

}  // namespace
}  // namespace physarum::testing
