// `physarum map` as a user runs it: one map on a mesh from --kind/--value/--arg (every input vertex
// gets the property, with the values the map's definition gives at its position, and a picture of the
// asked size), vector maps per face, helper maps from --maps, the usage errors (exit 2) of a
// malformed --arg or a mesh/scene mix-up, one picture per map of a scene, and the map cache seen
// from the command line ("from cache" on a second run, nothing stored with PHYSARUM_NO_CACHE=1).
#include "common/mesh/ply_reader.hpp"
#include "cache_environment.hpp"
#include "test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

namespace physarum {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::CacheEnvironment;
using testing::CommandResult;
using testing::quoted;
using testing::run_physarum;
using testing::TempDir;

std::array<int, 3> image_shape(const fs::path& p) {
  auto in = OIIO::ImageInput::open(p.string());
  if (!in) return {0, 0, 0};
  const OIIO::ImageSpec& s = in->spec();
  return {s.width, s.height, s.nchannels};
}

// Every child process of this test gets its own cache folder (or none), restored afterwards.

class MapCommand : public ::testing::Test {
 protected:
  CommandResult map(const std::string& args) { return run_physarum("map " + args); }
  TempDir dir_;
  CacheEnvironment cache_{dir_.path / "cache"};
};

TEST_F(MapCommand, OneMapOnAMeshIsWrittenOnEveryInputVertexWithAPicture) {
  const fs::path ply = dir_.path / "ramp.ply";
  const CommandResult r = map("shape:square --kind axis --value x --width 320 --height 240 --out " + quoted(ply));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PlyFields f = read_ply_fields(ply.string());
  // shape:square is a 32 x 32 grid of cells on [0, 1]^2: 33^2 vertices, and the ramp along x is x.
  ASSERT_EQ(f.mesh.vertex_count(), 33 * 33);
  const std::vector<double>& ramp = f.property("axis");
  ASSERT_EQ(ramp.size(), 33u * 33u);
  for (int v = 0; v < f.mesh.vertex_count(); ++v) EXPECT_NEAR(ramp[static_cast<size_t>(v)], f.mesh.positions[static_cast<size_t>(v)].x(), 1e-6);
  EXPECT_EQ(image_shape(dir_.path / "ramp.png"), (std::array<int, 3>{320, 240, 3}));
  EXPECT_NE(r.out.find("ramp.png"), std::string::npos) << r.out;
}

TEST_F(MapCommand, ArgsGoIntoTheKindsObjectAndASlashKeyBesideIt) {
  // {"sphere": {"center": [0.5, 0.5, 0], "radius": 0.2}, "falloff": 0.1}: 1 inside, 0 beyond 0.3,
  // 1 - smoothstep((d - 0.2) / 0.1) between.
  const fs::path ply = dir_.path / "blob.ply";
  const CommandResult r = map("shape:square --kind sphere --arg 'center=[0.5,0.5,0]' --arg radius=0.2 --arg /falloff=0.1 --name blob "
                              "--preview " + quoted(dir_.path / "pictures" / "blob.png") + " --out " + quoted(ply));
  ASSERT_EQ(r.exit_code, 1) << "the --preview folder does not exist: refused before anything is written\n" << r.err;
  EXPECT_FALSE(fs::exists(ply));
  fs::create_directories(dir_.path / "pictures");
  const CommandResult again = map("shape:square --kind sphere --arg 'center=[0.5,0.5,0]' --arg radius=0.2 --arg /falloff=0.1 --name blob "
                                  "--preview " + quoted(dir_.path / "pictures" / "blob.png") + " --out " + quoted(ply));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const PlyFields f = read_ply_fields(ply.string());
  const std::vector<double>& blob = f.property("blob");
  for (int v = 0; v < f.mesh.vertex_count(); ++v) {
    const double d = (f.mesh.positions[static_cast<size_t>(v)] - Eigen::Vector3d(0.5, 0.5, 0.0)).norm();
    const double t = std::clamp((d - 0.2) / 0.1, 0.0, 1.0);
    EXPECT_NEAR(blob[static_cast<size_t>(v)], d <= 0.2 ? 1.0 : 1.0 - t * t * (3.0 - 2.0 * t), 1e-6) << "at distance " << d;
  }
  EXPECT_EQ(image_shape(dir_.path / "pictures" / "blob.png")[0], 800);
}

TEST_F(MapCommand, RelativeRefinementIsTheMeshCommandsAtAnyScale) {
  // A circumradius bound relative to the bounding box does not change with --scale-to-area: the
  // triangulation is the one `physarum mesh` builds with the same fraction.
  const CommandResult mesh = run_physarum("mesh shape:square --max-circumradius-rel 0.01 --json");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const int vertices = json::parse(mesh.out)["intrinsic"]["vertices"].get<int>();
  ASSERT_GT(vertices, 33 * 33);
  const CommandResult r = map("shape:square --kind axis --value x --max-circumradius-rel 0.01 --scale-to-area 4 --no-preview --out " +
                              quoted(dir_.path / "x.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("intrinsic triangulation " + std::to_string(vertices) + " vertices"), std::string::npos) << r.out;
}

TEST_F(MapCommand, AVectorMapIsWrittenPerFaceWithAPicture) {
  // The square lies in z = 0: the direction (1, 0, 1) projects to (1, 0, 0) in every face.
  const fs::path ply = dir_.path / "east.ply";
  const CommandResult r = map("shape:square --kind direction --value '[1,0,1]' --name east --width 200 --height 150 --out " + quoted(ply));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PlyFields f = read_ply_fields(ply.string());
  ASSERT_EQ(f.face_property("east_x").size(), static_cast<size_t>(f.mesh.triangle_count()));
  for (int t = 0; t < f.mesh.triangle_count(); ++t) {
    EXPECT_NEAR(f.face_property("east_x")[static_cast<size_t>(t)], 1.0, 1e-6);
    EXPECT_NEAR(f.face_property("east_y")[static_cast<size_t>(t)], 0.0, 1e-6);
    EXPECT_NEAR(f.face_property("east_z")[static_cast<size_t>(t)], 0.0, 1e-6);
  }
  EXPECT_EQ(image_shape(dir_.path / "east.png"), (std::array<int, 3>{200, 150, 3}));
}

TEST_F(MapCommand, HelperMapsComeFromAFileAndOnlyTheAskedMapIsWritten) {
  std::ofstream(dir_.path / "helpers.json") << json{{"ramp", {{"axis", "y"}}}}.dump();
  const fs::path ply = dir_.path / "scaled.ply";
  const CommandResult r = map("shape:square --maps " + quoted(dir_.path / "helpers.json") +
                              " --kind map --value ramp --arg 'range=[2,4]' --name scaled --no-preview --out " + quoted(ply));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PlyFields f = read_ply_fields(ply.string());
  for (int v = 0; v < f.mesh.vertex_count(); ++v)
    EXPECT_NEAR(f.property("scaled")[static_cast<size_t>(v)], 2.0 + 2.0 * f.mesh.positions[static_cast<size_t>(v)].y(), 1e-6);
  EXPECT_EQ(f.properties.count("ramp"), 0u);
  EXPECT_FALSE(fs::exists(dir_.path / "scaled.png"));
  // A helper of the same name as the map is a usage error.
  const CommandResult clash = map("shape:square --maps " + quoted(dir_.path / "helpers.json") + " --kind axis --value x --name ramp");
  EXPECT_EQ(clash.exit_code, 2) << clash.err;
  EXPECT_NE(clash.err.find("already defines a map 'ramp'"), std::string::npos) << clash.err;
}

TEST_F(MapCommand, MalformedArgsAreUsageErrors) {
  const std::string out = " --out " + quoted(dir_.path / "x.ply");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--kind sphere --arg radius", "expected KEY=VALUE"},
      {"--kind sphere --arg =0.2", "the key before '=' is empty"},
      {"--kind sphere --arg 'center=[0,0'", "not valid JSON"},
      {"--kind sphere --arg radius=1 --arg radius=2", "/sphere/radius is given twice"},
      {"--kind axis --value x --arg /axis/y=1", "is not an object of fields"},
      {"--kind axis --value x --arg axis=y", "give it with --value"},
      {"--kind sphere --value '{\"radius\":'", "not valid JSON"},
  };
  for (const auto& [args, message] : cases) {
    const CommandResult r = map("shape:square " + args + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(dir_.path / "x.ply"));
  // A kind the map table does not know is refused by the scene's own parser (bad input), listing the known ones.
  const CommandResult unknown = map("shape:square --kind geodesic_distanse" + out);
  EXPECT_EQ(unknown.exit_code, 1) << unknown.err;
  EXPECT_NE(unknown.err.find("no known map source"), std::string::npos) << unknown.err;
}

TEST_F(MapCommand, AMeshNeedsAKindAndASceneTakesNone) {
  const CommandResult no_kind = map("shape:square --out " + quoted(dir_.path / "x.ply"));
  EXPECT_EQ(no_kind.exit_code, 2) << no_kind.err;
  EXPECT_NE(no_kind.err.find("needs --kind"), std::string::npos) << no_kind.err;
  std::ofstream(dir_.path / "scene.json") << "{}";
  const CommandResult scene_kind = map(quoted(dir_.path / "scene.json") + " --kind axis --value x --max-circumradius 0.1");
  EXPECT_EQ(scene_kind.exit_code, 2) << scene_kind.err;
  EXPECT_NE(scene_kind.err.find("--kind, --value, the surface options"), std::string::npos) << scene_kind.err;
}

// A valid scene on the unit square with two maps.
json scene_with_maps() {
  return {{"mesh", "shape:square"},  {"agents", 200},        {"time_step", 0.02},      {"sensor_distance", 0.05},
          {"sensor_angle", 22.5},    {"move_rate", 0.5},     {"turn_rate", 180.0},     {"turn_frequency", 20.0},
          {"deposit_rate", 1.0},     {"decay_rate", 1.0},    {"diffuse_rate", 0.0002}, {"mean_lifetime", 1.0},
          {"maps", {{"ramp", {{"axis", "x"}}}, {"east", {{"direction", {1.0, 0.0, 0.0}}}}}}};
}

TEST_F(MapCommand, ASceneGetsOnePicturePerMapAndASecondRunReadsTheCache) {
  std::ofstream(dir_.path / "scene.json") << scene_with_maps().dump();
  const std::string args = quoted(dir_.path / "scene.json") + " --width 160 --height 120 --out " + quoted(dir_.path / "maps.ply");
  const CommandResult first = map(args);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.err.find("maps: 2 computed"), std::string::npos) << first.err;
  EXPECT_EQ(image_shape(dir_.path / "maps_ramp.png"), (std::array<int, 3>{160, 120, 3}));
  EXPECT_EQ(image_shape(dir_.path / "maps_east.png"), (std::array<int, 3>{160, 120, 3}));
  const CommandResult second = map(args);
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.err.find("maps: 2 from cache"), std::string::npos) << second.err;
  EXPECT_EQ(read_ply_fields((dir_.path / "maps.ply").string()).property("ramp").size(), 33u * 33u);
}

TEST_F(MapCommand, NoCacheComputesEveryTimeAndStoresNothing) {
  const CacheEnvironment off(dir_.path / "off", /*off=*/true);
  for (int round = 0; round < 2; ++round) {
    const CommandResult r = map("shape:square --kind axis --value x --no-preview --out " + quoted(dir_.path / "x.ply"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("maps: 1 computed, "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(cache off)"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir_.path / "off"));
}

}  // namespace
}  // namespace physarum
