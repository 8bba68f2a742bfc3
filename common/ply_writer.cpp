#include "common/ply_writer.hpp"

#include "common/atomic_write.hpp"
#include "common/errors.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace physarum {
namespace {

// Appends the little-endian bytes of a 4-byte value whatever the host's byte order.
template <typename T>
void append_le(std::vector<unsigned char>& out, T value) {
  static_assert(sizeof(T) == 4);
  const auto bits = std::bit_cast<std::uint32_t>(value);
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<unsigned char>((bits >> (8 * b)) & 0xFFu));
}

}  // namespace

void write_field_ply(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                     const FieldColoring& coloring, const std::string& property_name) {
  if (static_cast<int>(values.size()) != mesh.vertex_count())
    throw InputError(path + ": cannot write " + std::to_string(values.size()) + " values onto the " +
                     std::to_string(mesh.vertex_count()) + " vertices of " + mesh.source);

  std::string header = "ply\nformat binary_little_endian 1.0\ncomment physarum: " + property_name +
                       " per input vertex\nelement vertex " + std::to_string(mesh.vertex_count()) +
                       "\nproperty float x\nproperty float y\nproperty float z\nproperty float " + property_name +
                       "\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face " +
                       std::to_string(mesh.triangle_count()) + "\nproperty list uchar int vertex_indices\nend_header\n";

  std::vector<unsigned char> body;
  body.reserve(static_cast<size_t>(mesh.vertex_count()) * 19 + static_cast<size_t>(mesh.triangle_count()) * 13);
  const double upper_end = coloring.upper(values);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) append_le(body, static_cast<float>(mesh.positions[v][c]));
    append_le(body, static_cast<float>(values[v]));
    const Rgb8 rgb = coloring.color(values[v], upper_end);
    body.insert(body.end(), rgb.begin(), rgb.end());
  }
  for (const auto& t : mesh.triangles) {
    body.push_back(3);
    for (int c = 0; c < 3; ++c) append_le(body, static_cast<std::int32_t>(t[c]));
  }

  write_file_atomically(path, [&](const std::string& temporary) {
    std::FILE* f = std::fopen(temporary.c_str(), "wb");
    if (!f) throw InputError(path + ": cannot write: " + std::strerror(errno));
    bool ok = std::fwrite(header.data(), 1, header.size(), f) == header.size();
    ok = ok && std::fwrite(body.data(), 1, body.size(), f) == body.size();
    const int saved_errno = errno;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) throw InputError(path + ": cannot write: " + std::strerror(saved_errno ? saved_errno : errno));
  });
}

}  // namespace physarum
