#pragma once
// An independent reader, for the tests, of exactly the layout common/output/ply_writer.hpp documents
// (binary little-endian; vertex: float x, y, z, one float per field, uchar red, green, blue; face:
// list uchar int vertex_indices), parsed byte by byte from the header's own declarations. It shares
// no code with the writer or with common/mesh/ply_reader, so a round trip checks the files themselves.
#include "common/color/color_map.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace physarum::testing {

struct ParsedPly {
  std::vector<std::string> header;  // the header's lines, "ply" to the last before end_header
  int vertices = -1, faces = -1;
  std::vector<std::string> float_properties;  // vertex float properties in file order (x, y, z first)
  std::vector<std::vector<float>> vertex;     // per vertex, the float properties in that order
  std::vector<Rgb8> color;
  std::vector<std::array<int, 3>> face;

  // The values of float property `name`, one per vertex (empty when absent).
  std::vector<float> property(const std::string& name) const {
    std::vector<float> out;
    for (size_t p = 0; p < float_properties.size(); ++p)
      if (float_properties[p] == name)
        for (const auto& v : vertex) out.push_back(v[p]);
    return out;
  }
};

inline ParsedPly parse_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ParsedPly ply;
  const size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  if (end == std::string::npos) return ply;
  std::stringstream header(bytes.substr(0, end));
  std::string element;
  int colour_bytes = 0;
  for (std::string line; std::getline(header, line);) {
    ply.header.push_back(line);
    std::stringstream words(line);
    std::string a, b, c;
    words >> a >> b >> c;
    if (a == "element") {
      element = b;
      if (b == "vertex") ply.vertices = std::stoi(c);
      if (b == "face") ply.faces = std::stoi(c);
    }
    if (a == "property" && element == "vertex") {
      if (b == "float") {
        EXPECT_EQ(colour_bytes, 0) << "float property " << c << " after the colours";
        ply.float_properties.push_back(c);
      } else {
        EXPECT_EQ(b, "uchar") << line;
        ++colour_bytes;
      }
    }
  }
  EXPECT_EQ(colour_bytes, 3);
  size_t at = end + std::strlen("end_header\n");
  auto take = [&](void* out, size_t size) {
    EXPECT_LE(at + size, bytes.size());
    if (at + size > bytes.size()) return;
    std::memcpy(out, bytes.data() + at, size);  // the test machine is little-endian, like the file
    at += size;
  };
  for (int v = 0; v < ply.vertices; ++v) {
    std::vector<float> values(ply.float_properties.size());
    Rgb8 rgb;
    take(values.data(), 4 * values.size());
    take(rgb.data(), 3);
    ply.vertex.push_back(std::move(values));
    ply.color.push_back(rgb);
  }
  for (int f = 0; f < ply.faces; ++f) {
    unsigned char count = 0;
    take(&count, 1);
    EXPECT_EQ(count, 3);
    std::array<int, 3> t;
    take(t.data(), 12);
    ply.face.push_back(t);
  }
  EXPECT_EQ(at, bytes.size()) << "trailing bytes after the last face";
  return ply;
}

}  // namespace physarum::testing
