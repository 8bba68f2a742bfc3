// Bad mesh input: for every class of problem, a tiny file in a temporary folder must give an
// InputError whose message names the file and the offending element — through load_mesh, through
// `physarum mesh FILE --json` (exit 1, message on stderr, nothing on stdout, no file written) and
// through `physarum run` of a scene whose mesh is that file (exit 1, no output folder). Each bad
// file is its own parameterized test case, named after the file.
#include "common/base/errors.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

namespace physarum {
namespace {

struct BadFile {
  std::string name;                   // file name inside the temporary folder
  std::string content;                // bytes written
  std::vector<std::string> expected;  // substrings the message must contain (besides the path)
  bool create = true;                 // false: the file does not exist at all
};

// One triangle with a NaN in a binary PLY: the number arrives as a float, not as text, so only
// the coordinate check can catch it.
std::string binary_ply_with_nan() {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&](auto x) { s.append(reinterpret_cast<const char*>(&x), sizeof x); };
  for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, std::numeric_limits<float>::quiet_NaN(), 1.f, 0.f}) put(x);
  put(static_cast<unsigned char>(3));
  for (std::int32_t v : {0, 1, 2}) put(v);
  return s;
}

// A Moebius strip: 8 quads (16 triangles) around a circle, the last joined to the first with a
// half twist.
std::string moebius_obj() {
  std::string s;
  const int n = 8;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    for (double w : {-0.3, 0.3}) {
      const double r = 1 + w * std::cos(a / 2);
      s += "v " + std::to_string(r * std::cos(a)) + " " + std::to_string(r * std::sin(a)) + " " + std::to_string(w * std::sin(a / 2)) + "\n";
    }
  }
  for (int i = 0; i < n; ++i) {
    const int a0 = 2 * i + 1, b0 = 2 * i + 2;
    const int a1 = i + 1 < n ? 2 * i + 3 : 2, b1 = i + 1 < n ? 2 * i + 4 : 1;  // the twist swaps the sides
    s += "f " + std::to_string(a0) + " " + std::to_string(a1) + " " + std::to_string(b1) + "\n";
    s += "f " + std::to_string(a0) + " " + std::to_string(b1) + " " + std::to_string(b0) + "\n";
  }
  return s;
}

const std::string square_vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

std::vector<BadFile> bad_files() {
  return {
      {"nonmanifold.obj", square_vertices + "v 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n", {"non-manifold edge between vertices 0 and 1", "3 faces"}},
      {"moebius.obj", moebius_obj(), {"not orientable", "Möbius"}},
      {"range.obj", square_vertices + "f 1 2 3\nf 1 3 9\n", {"face 1 refers to vertex 8", "only 4 vertices"}},
      {"negative.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 -1\n", {"face 1 refers to vertex -1"}},
      {"nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", {"line 3", "vertex 2", "non-finite"}},
      {"inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n", {"line 5", "non-finite number 'inf'"}},
      {"nan.ply", binary_ply_with_nan(), {"vertex 2 has a non-finite coordinate"}},
      {"empty.obj", square_vertices, {"no faces"}},
      {"only-repeated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n", {"no faces"}},
      {"collinear.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 2 3 4\nf 1 3 2\n", {"zero-area face 2"}},
      {"garbage.ply", "this is not a ply file\n", {"could not parse"}},
      {"unknown.xyz", "v 0 0 0\n", {"unsupported mesh file extension '.xyz'"}},
      // 0 bytes (an interrupted copy): said plainly, whatever the format.
      {"zero-bytes.obj", "", {"the file is empty (0 bytes)"}},
      {"zero-bytes.ply", "", {"the file is empty (0 bytes)"}},
      {"no-such-file.obj", "", {"no such file"}, false},
  };
}

// gtest prints a failing case's parameter: its file name, not its bytes.
void PrintTo(const BadFile& bad, std::ostream* os) { *os << bad.name; }

std::string test_name(const ::testing::TestParamInfo<BadFile>& info) {
  std::string name = info.param.name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

// The entries of a folder, by name.
std::set<std::string> folder_entries(const std::filesystem::path& folder) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(folder)) names.insert(e.path().filename().string());
  return names;
}

class BadMeshFile : public ::testing::TestWithParam<BadFile> {
 protected:
  // Writes the bad file (unless it is the missing-file case) and returns its path.
  std::string write_bad_file() {
    const BadFile& bad = GetParam();
    const std::string path = (dir_.path / bad.name).string();
    if (bad.create) std::ofstream(path, std::ios::binary) << bad.content;
    return path;
  }
  testing::TempDir dir_;
};

void expect_message(const std::string& message, const std::string& path, const std::vector<std::string>& expected) {
  EXPECT_NE(message.find(path), std::string::npos) << "message does not name the file: " << message;
  for (const auto& e : expected) EXPECT_NE(message.find(e), std::string::npos) << "missing '" << e << "' in: " << message;
}

TEST_P(BadMeshFile, LoadMeshThrowsAnInputErrorNamingFileAndElement) {
  const std::string path = write_bad_file();
  try {
    load_mesh(path);
    ADD_FAILURE() << "no InputError for " << GetParam().name;
  } catch (const InputError& e) {
    expect_message(e.what(), path, GetParam().expected);
  }
}

TEST_P(BadMeshFile, MeshCommandExitsOneWithTheMessageOnStderrOnly) {
  const std::string path = write_bad_file();
  const std::set<std::string> before = folder_entries(dir_.path);
  const auto r = testing::run_physarum("mesh '" + path + "' --json");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << "stdout must stay empty (no partial JSON): " << r.out;
  expect_message(r.err, path, GetParam().expected);
  EXPECT_EQ(folder_entries(dir_.path), before) << "nothing may be written beside the input";
}

// The same file as the mesh of a scene: `physarum run` refuses it before creating the output folder.
// (A missing file is caught by the scene reader, which names the key and the path it looked for.)
TEST_P(BadMeshFile, RunCommandExitsOneAndWritesNothing) {
  const std::string path = write_bad_file();
  const auto scene = dir_.path / "scene.json";
  std::ofstream(scene) << R"({"mesh": ")" << GetParam().name << R"(", "agents": 10, "time_step": 0.01,
    "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
    "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
    "mean_lifetime": null, "steps": 5})";
  const std::set<std::string> before = folder_entries(dir_.path);
  const auto out = dir_.path / "out";
  const auto r = testing::run_physarum("run '" + scene.string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  expect_message(r.err, path,
                 GetParam().create ? GetParam().expected : std::vector<std::string>{"key 'mesh'", "file not found"});
  EXPECT_FALSE(std::filesystem::exists(out)) << "the output folder was created for a refused input";
  EXPECT_EQ(folder_entries(dir_.path), before) << "nothing may be written";
}

INSTANTIATE_TEST_SUITE_P(MeshErrors, BadMeshFile, ::testing::ValuesIn(bad_files()), test_name);

TEST(MeshErrors, MissingFileIsNamed) {
  const std::string path = "/nonexistent-folder/no-such-mesh.obj";
  try {
    load_mesh(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    expect_message(e.what(), path, {"no such file"});
  }
}

TEST(MeshErrors, RepeatedIndexFaceIsDroppedWithAWarning) {
  testing::TempDir dir;
  const std::string path = (dir.path / "repeated.off").string();
  std::ofstream(path) << "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 2 3 2\n";
  const InputMesh m = load_mesh(path);
  EXPECT_EQ(m.triangle_count(), 1);
  ASSERT_EQ(m.warnings.size(), 2u);
  EXPECT_NE(m.warnings[0].find("repeated vertex index (the first is face 1, which uses vertex 2 twice)"), std::string::npos) << m.warnings[0];
  EXPECT_NE(m.warnings[1].find("dropped 1 vertex used by no face"), std::string::npos) << m.warnings[1];

  // OpenMesh's OBJ reader removes repeated corners itself; the loader still says so.
  const std::string obj = (dir.path / "repeated.obj").string();
  std::ofstream(obj) << square_vertices << "f 1 2 3\nf 1 3 3 4\n";
  const InputMesh o = load_mesh(obj);
  EXPECT_EQ(o.triangle_count(), 2);
  ASSERT_FALSE(o.warnings.empty());
  EXPECT_NE(o.warnings[0].find("1 face lists a vertex more than once (the first is face 1)"), std::string::npos) << o.warnings[0];
}

TEST(MeshErrors, InconsistentButOrientableFileIsRepairedNotRejected) {
  testing::TempDir dir;
  const std::string path = (dir.path / "flipped.obj").string();
  std::ofstream(path) << square_vertices << "f 1 2 3\nf 1 4 3\n";
  const InputMesh m = load_mesh(path);
  ASSERT_EQ(m.triangle_count(), 2);
  EXPECT_EQ(m.warnings.size(), 1u);
  for (const auto& t : m.triangles)
    EXPECT_GT((m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).z(), 0);
}

TEST(MeshErrors, UnknownShapeListsTheValidOnes) {
  const auto shape = testing::run_physarum("mesh shape:nope --json");
  EXPECT_EQ(shape.exit_code, 1);
  EXPECT_TRUE(shape.out.empty());
  EXPECT_NE(shape.err.find("skinny-sphere"), std::string::npos) << shape.err;
}

}  // namespace
}  // namespace physarum
