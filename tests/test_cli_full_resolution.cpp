// `physarum run` on a mesh file with UVs, as a user runs it: besides pheromone.ply it writes the
// full-resolution fields_full.ply (one vertex per intrinsic vertex, agreeing with pheromone.ply on
// the input vertices) and texture.png (or .exr / 16-bit PNG as asked), leaves no temporary files,
// refuses a UV map it cannot bake before writing anything, and notes a mesh without UVs.
#include "common/mesh/input_mesh.hpp"
#include "ply_layout_parser.hpp"
#include "test_support.hpp"
#include "uv_test_meshes.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;

// The mesh as an OBJ file with per-corner texture coordinates (v, vt, f v/vt).
void write_obj(const fs::path& path, const InputMesh& mesh) {
  std::ofstream out(path);
  out.precision(17);
  for (const auto& p : mesh.positions) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const auto& uv : mesh.uvs) out << "vt " << uv.x() << ' ' << uv.y() << '\n';
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    out << 'f';
    for (int c = 0; c < 3; ++c) out << ' ' << mesh.triangles[t][c] + 1 << '/' << mesh.triangle_uvs[t][c] + 1;
    out << '\n';
  }
}

void write_scene(const fs::path& path, const std::string& mesh) {
  std::ofstream(path) << R"({
  "mesh": ")" << mesh << R"(", "scale_to_area": 1.0, "agents": 300, "time_step": 0.02, "max_circumradius": 0.05,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward", "seed": 3
})";
}

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

OIIO::ImageSpec image_spec(const fs::path& p) {
  auto in = OIIO::ImageInput::open(p.string());
  EXPECT_TRUE(in) << p << ": " << OIIO::geterror();
  return in ? in->spec() : OIIO::ImageSpec();
}

class FullResolutionRun : public ::testing::Test {
 protected:
  void SetUp() override {
    write_obj(dir_.path / "rectangle.obj", make_uv_rectangle());
    write_scene(dir_.path / "scene.json", "rectangle.obj");
  }
  CommandResult run(const std::string& out, const std::string& flags) {
    return run_physarum("run " + quoted(dir_.path / "scene.json") + " --backend reference --steps 10 --texture-size 64 " +
                        flags + " --out " + quoted(dir_.path / out));
  }
  TempDir dir_;
};

TEST_F(FullResolutionRun, WritesFieldsFullAndTexture) {
  const CommandResult r = run("out", "");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path out = dir_.path / "out";
  EXPECT_EQ(files_in(out), (std::vector<std::string>{"fields_full.ply", "pheromone.ply", "preview.png", "result.glb",
                                                      "run.json", "stats.csv", "texture.png"}));
  EXPECT_NE(r.out.find("fields_full.ply"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("texture.png"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;

  std::ifstream run_json(out / "run.json");
  const nlohmann::json j = nlohmann::json::parse(run_json);
  const ParsedPly full = parse_ply((out / "fields_full.ply").string());
  const ParsedPly on_input = parse_ply((out / "pheromone.ply").string());
  ASSERT_EQ(full.vertices, j["intrinsic_vertices"].get<int>());
  ASSERT_EQ(full.faces, j["intrinsic_faces"].get<int>());
  ASSERT_GT(full.vertices, 2 * on_input.vertices) << "the run's refinement inserted vertices";
  EXPECT_EQ(full.float_properties, (std::vector<std::string>{"x", "y", "z", "pheromone"}));
  // The input vertices are the first intrinsic vertices: same positions, same values, same colours.
  const std::vector<float> full_values = full.property("pheromone"), input_values = on_input.property("pheromone");
  for (int v = 0; v < on_input.vertices; ++v) {
    for (int c = 0; c < 3; ++c) ASSERT_EQ(full.vertex[v][c], on_input.vertex[v][c]) << v;
    ASSERT_EQ(full_values[v], input_values[v]) << v;
    ASSERT_EQ(full.color[v], on_input.color[v]) << v;
  }
  const OIIO::ImageSpec texture = image_spec(out / "texture.png");
  EXPECT_EQ(texture.width, 64);
  EXPECT_EQ(texture.height, 64);
  EXPECT_EQ(texture.nchannels, 3);
  EXPECT_EQ(texture.format, OIIO::TypeDesc::UINT8);
}

TEST_F(FullResolutionRun, ExrAndSixteenBitFormats) {
  const CommandResult exr = run("exr", "--texture-format exr --texture-margin 4");
  ASSERT_EQ(exr.exit_code, 0) << exr.err;
  EXPECT_TRUE(fs::exists(dir_.path / "exr" / "texture.png"));
  const OIIO::ImageSpec exr_spec = image_spec(dir_.path / "exr" / "texture.exr");
  EXPECT_EQ(exr_spec.width, 64);
  EXPECT_EQ(exr_spec.channelnames, std::vector<std::string>{"pheromone"});
  EXPECT_EQ(exr_spec.format, OIIO::TypeDesc::FLOAT);

  const CommandResult png16 = run("png16", "--texture-format png16");
  ASSERT_EQ(png16.exit_code, 0) << png16.err;
  EXPECT_EQ(image_spec(dir_.path / "png16" / "texture.png").format, OIIO::TypeDesc::UINT16);
  EXPECT_FALSE(fs::exists(dir_.path / "png16" / "texture.exr"));
}

TEST_F(FullResolutionRun, BadTextureRequestsWriteNothing) {
  // Usage errors: exit 2, no output folder.
  for (const char* flags : {"--texture-size 0", "--texture-size 100000", "--texture-margin -1", "--texture-format jpg"}) {
    const CommandResult r = run("bad", flags);
    EXPECT_EQ(r.exit_code, 2) << flags << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_.path / "bad")) << flags;
  }
  // A UV map that cannot be baked (a triangle across more than one tile): bad input, exit 1,
  // refused before simulating, nothing written.
  InputMesh mesh = make_uv_rectangle();
  mesh.uvs.push_back(mesh.uvs[static_cast<size_t>(mesh.triangle_uvs[3][0])] + Eigen::Vector2d(0.0, 2.5));
  mesh.triangle_uvs[3][0] = static_cast<int>(mesh.uvs.size()) - 1;
  write_obj(dir_.path / "stretched.obj", mesh);
  write_scene(dir_.path / "stretched.json", "stretched.obj");
  const CommandResult r = run_physarum("run " + quoted(dir_.path / "stretched.json") + " --backend reference --steps 10 --out " +
                                       quoted(dir_.path / "stretched"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("spans more than one texture tile"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_.path / "stretched"));
}

TEST_F(FullResolutionRun, MeshWithoutUvsSkipsTheTextureWithANote) {
  write_scene(dir_.path / "square.json", "shape:square");
  const CommandResult r = run_physarum("run " + quoted(dir_.path / "square.json") + " --backend reference --steps 5 --out " +
                                       quoted(dir_.path / "square"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("no texture coordinates"), std::string::npos) << r.err;
  EXPECT_EQ(files_in(dir_.path / "square"),
            (std::vector<std::string>{"fields_full.ply", "pheromone.ply", "preview.png", "result.glb", "run.json", "stats.csv"}));
}

TEST(FullResolutionRunHelp, NamesTheNewOutputsAndFlags) {
  const CommandResult r = run_physarum("run --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* text : {"fields_full.ply", "texture.png", "--texture-size", "--texture-margin", "--texture-format",
                           "png16", "exr"})
    EXPECT_NE(r.out.find(text), std::string::npos) << "'" << text << "' missing from:\n" << r.out;
}

}  // namespace
}  // namespace physarum::testing
