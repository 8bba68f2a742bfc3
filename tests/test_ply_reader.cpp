// Reading results back (common/mesh/ply_reader): what write_field_ply wrote comes back exactly (float
// values are stored as float, so the round trip is exact for float-representable inputs), and every
// malformed file is refused with its name and the problem.
#include "common/base/errors.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/output/ply_writer.hpp"
#include "pheromone_test_meshes.hpp"
#include "ply_formats.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <fstream>

namespace physarum {
namespace {

using testing::TempDir;

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(PlyReader, ReadsBackWhatTheWriterWrote) {
  const InputMesh mesh = testing::make_icosphere(2);
  InputVertexData<double> values(mesh.positions.size());
  // Values that are exact in float, so the round trip must be bit-exact.
  for (size_t v = 0; v < values.size(); ++v) values[v] = 0.25 * static_cast<double>(v % 17);
  TempDir dir;
  const std::string path = (dir.path / "pheromone.ply").string();
  FieldColoring coloring;
  coloring.high = 4.0;
  write_field_ply(path, mesh, values, coloring);

  const PlyFields ply = read_ply_fields(path);
  ASSERT_EQ(ply.mesh.vertex_count(), mesh.vertex_count());
  ASSERT_EQ(ply.mesh.triangles, mesh.triangles);
  for (int v = 0; v < mesh.vertex_count(); ++v)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(ply.mesh.positions[v][c], static_cast<float>(mesh.positions[v][c]));
  EXPECT_EQ(ply.property_names, (std::vector<std::string>{"pheromone", "red", "green", "blue"}));
  ASSERT_EQ(ply.property("pheromone"), std::vector<double>(values.begin(), values.end()));
  // Value 0 is the bottom of the colour range: viridis' first colour, #440154.
  EXPECT_EQ(ply.property("red")[0], 0x44);
  EXPECT_EQ(ply.property("blue")[0], 0x54);
  EXPECT_THROW(
      {
        try {
          (void)ply.property("age");
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("pheromone"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
}

TEST(PlyReader, RefusesMalformedFilesNamingThem) {
  TempDir dir;
  const auto expect_refused = [&](const std::string& bytes, const std::string& says) {
    const auto path = dir.path / "bad.ply";
    write_bytes(path, bytes);
    try {
      (void)read_ply_fields(path.string());
      ADD_FAILURE() << "accepted a file that should say: " << says;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_NE(message.find(says), std::string::npos) << message;
    }
  };
  const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body(36, '\0');
  std::string face = {3};
  for (int i : {0, 1, 2}) face += std::string{static_cast<char>(i), 0, 0, 0};
  // The well-formed file is accepted (so the refusals below are about their one defect).
  write_bytes(dir.path / "good.ply", head + body + face);
  EXPECT_EQ(read_ply_fields((dir.path / "good.ply").string()).mesh.triangle_count(), 1);

  expect_refused(head + body + face.substr(0, 7), "truncated");
  expect_refused(head + body + face + "x", "after the last element");
  std::string quad = face;
  quad[0] = 4;
  expect_refused(head + body + quad + std::string(4, '\0'), "not a triangle");
  std::string out_of_range = face;
  out_of_range[9] = 7;
  expect_refused(head + body + out_of_range, "out of range");
  std::string unknown = head;
  unknown.replace(unknown.find("binary_little_endian"), 20, "binary_middle_endian");
  expect_refused(unknown, "binary_middle_endian");
  std::string ascii_head = head;
  ascii_head.replace(ascii_head.find("binary_little_endian"), 20, "ascii");
  expect_refused(ascii_head + "0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n", "'zero' at byte");
  expect_refused(ascii_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "truncated");
  expect_refused("solid x\n", "not a PLY");
  try {
    (void)read_ply_fields((dir.path / "missing.ply").string());
    ADD_FAILURE() << "read a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

// ASCII (trimesh, Blender's exporter option, scripts) and big-endian PLYs, written by the test, read
// back to the same bits as the little-endian one; CR LF line ends too.
TEST(PlyReader, ReadsAsciiAndBigEndianFilesAsTheLittleEndianOne) {
  const InputMesh mesh = testing::make_icosphere(2);
  std::vector<float> values(mesh.positions.size());
  for (size_t v = 0; v < values.size(); ++v) values[v] = std::sin(0.37f * static_cast<float>(v)) * 3.0e-3f + 1.0f / 3.0f;
  TempDir dir;
  std::vector<PlyFields> read;
  for (const char* format : {"binary_little_endian", "binary_big_endian", "ascii"}) {
    const std::string path = (dir.path / (std::string(format) + ".ply")).string();
    testing::write_ply_in_format(path, format, mesh, "w", values);
    read.push_back(read_ply_fields(path));
  }
  ASSERT_EQ(read[0].property("w"), std::vector<double>(values.begin(), values.end()));
  for (size_t k = 1; k < read.size(); ++k) {
    EXPECT_EQ(read[k].mesh.positions, read[0].mesh.positions) << k;
    EXPECT_EQ(read[k].mesh.triangles, mesh.triangles) << k;
    EXPECT_EQ(read[k].property("w"), read[0].property("w")) << k;
  }
  // Windows line ends in an ASCII file.
  std::ifstream in(dir.path / "ascii.ply", std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write_bytes(dir.path / "crlf.ply", crlf);
  EXPECT_EQ(read_ply_fields((dir.path / "crlf.ply").string()).property("w"), read[0].property("w"));
}

// Face properties (a map's per-face vectors, other tools' per-face values): scalars declared before
// and after the vertex-index list are read in the header's order, one value per face.
TEST(PlyReader, ReadsFacePropertiesAroundTheIndexList) {
  TempDir dir;
  const std::string head =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty uchar flag\nproperty list uchar int vertex_indices\nproperty float quality\n"
      "property double q2\nend_header\n";
  std::string body(48, '\0');
  auto le = [](auto value) {
    std::string bytes(sizeof(value), '\0');
    std::memcpy(bytes.data(), &value, sizeof(value));  // the test host is little-endian (x86-64)
    return bytes;
  };
  for (int f = 0; f < 2; ++f) {
    body += std::string(1, static_cast<char>(7 + f));  // flag
    body += std::string(1, 3);
    for (int i : {0, 1 + f, 2 + f}) body += le(static_cast<std::int32_t>(i));
    body += le(0.5f + static_cast<float>(f));  // quality
    body += le(-2.25 * (f + 1));               // q2
  }
  write_bytes(dir.path / "faces.ply", head + body);
  const PlyFields ply = read_ply_fields((dir.path / "faces.ply").string());
  EXPECT_EQ(ply.face_property_names, (std::vector<std::string>{"flag", "quality", "q2"}));
  EXPECT_EQ(ply.face_property("flag"), (std::vector<double>{7, 8}));
  EXPECT_EQ(ply.face_property("quality"), (std::vector<double>{0.5, 1.5}));
  EXPECT_EQ(ply.face_property("q2"), (std::vector<double>{-2.25, -4.5}));
  EXPECT_EQ(ply.mesh.triangles, (std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}}));
  try {
    (void)ply.face_property("normal_x");
    ADD_FAILURE() << "found a face property the file does not have";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no face property 'normal_x' (it has: flag, quality, q2)"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace physarum
