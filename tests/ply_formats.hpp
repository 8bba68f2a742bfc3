#pragma once
// The same PLY in the three formats the standard has (ascii, binary_little_endian,
// binary_big_endian), written by the test itself, not by physarum's writer: a mesh's vertices (x, y,
// z as float), one float vertex property, and its triangles (uchar count, int indices). Floats are
// printed with 9 significant digits in ASCII, which round-trips every float exactly.
#include "common/mesh/input_mesh.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace physarum::testing {

inline void write_ply_in_format(const std::string& path, const std::string& format, const InputMesh& mesh,
                                const std::string& property, const std::vector<float>& values) {
  std::string out = "ply\nformat " + format + " 1.0\ncomment written by a physarum test\nelement vertex " +
                    std::to_string(mesh.vertex_count()) + "\nproperty float x\nproperty float y\nproperty float z\nproperty float " +
                    property + "\nelement face " + std::to_string(mesh.triangle_count()) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
  const bool big = format == "binary_big_endian";
  auto bytes = [&](const void* p, size_t n) {
    std::string b(static_cast<const char*>(p), n);
    if (big) b = std::string(b.rbegin(), b.rend());  // the test host is little-endian (x86-64)
    out += b;
  };
  auto number = [&](float x) {
    if (format == "ascii") {
      char text[32];
      std::snprintf(text, sizeof text, "%.9g ", static_cast<double>(x));
      out += text;
    } else {
      bytes(&x, sizeof x);
    }
  };
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) number(static_cast<float>(mesh.positions[static_cast<size_t>(v)][c]));
    number(values[static_cast<size_t>(v)]);
    if (format == "ascii") out += "\n";
  }
  for (const auto& t : mesh.triangles) {
    if (format == "ascii") {
      out += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
      continue;
    }
    out += std::string(1, 3);
    for (int c = 0; c < 3; ++c) {
      const std::int32_t i = t[static_cast<size_t>(c)];
      bytes(&i, sizeof i);
    }
  }
  std::ofstream(path, std::ios::binary) << out;
}

}  // namespace physarum::testing
