#include "common/output/ply_writer.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace physarum {
namespace {

// Writes the little-endian bytes of a 4-byte value at `out` whatever the host's byte order; returns
// the position after them.
template <typename T>
unsigned char* put_le(unsigned char* out, T value) {
  static_assert(sizeof(T) == 4);
  const auto bits = std::bit_cast<std::uint32_t>(value);
  for (int b = 0; b < 4; ++b) *out++ = static_cast<unsigned char>((bits >> (8 * b)) & 0xFFu);
  return out;
}

// A PLY property name this writer accepts: a non-empty word of letters, digits, '_' and '-' (no
// whitespace, which would end the header token) that is not one of the other vertex properties.
bool usable_property_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  for (const char* taken : {"x", "y", "z", "red", "green", "blue"})
    if (name == taken) return false;
  return true;
}

}  // namespace

void write_fields_ply(const std::string& path, const InputMesh& mesh, const std::vector<PlyField>& fields,
                      const FieldColoring& coloring, const std::string& description) {
  if (fields.empty()) throw InputError(path + ": no field to write");
  write_fields_ply(path, mesh, fields, {}, coloring, description);
}

void write_fields_ply(const std::string& path, const InputMesh& mesh, const std::vector<PlyField>& fields,
                      const std::vector<PlyFaceField>& face_fields, const FieldColoring& coloring,
                      const std::string& description) {
  if (fields.empty() && face_fields.empty()) throw InputError(path + ": no field to write");
  std::vector<std::string> names;
  auto check_name = [&](const std::string& name) {
    if (!usable_property_name(name))
      throw InputError(path + ": '" + name +
                       "' cannot be a PLY property name (letters, digits, '_' and '-' only; not x, y, z, red, green, blue)");
    if (std::find(names.begin(), names.end(), name) != names.end())
      throw InputError(path + ": field '" + name + "' given twice");
    names.push_back(name);
  };
  for (const PlyField& field : fields) {
    check_name(field.name);
    if (static_cast<int>(field.values.size()) != mesh.vertex_count())
      throw InputError(path + ": cannot write " + std::to_string(field.values.size()) + " values of " + field.name +
                       " onto the " + std::to_string(mesh.vertex_count()) + " vertices of " + mesh.source);
  }
  for (const PlyFaceField& field : face_fields) {
    check_name(field.name);
    if (static_cast<int>(field.values.size()) != mesh.triangle_count())
      throw InputError(path + ": cannot write " + std::to_string(field.values.size()) + " values of " + field.name +
                       " onto the " + std::to_string(mesh.triangle_count()) + " faces of " + mesh.source);
  }
  const bool coloured = !fields.empty();

  std::string header = "ply\nformat binary_little_endian 1.0\ncomment physarum: " + description +
                       "\nelement vertex " + std::to_string(mesh.vertex_count()) +
                       "\nproperty float x\nproperty float y\nproperty float z\n";
  for (const PlyField& field : fields) header += "property float " + field.name + "\n";
  if (coloured) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header += "element face " + std::to_string(mesh.triangle_count()) + "\nproperty list uchar int vertex_indices\n";
  for (const PlyFaceField& field : face_fields) header += "property float " + field.name + "\n";
  header += "end_header\n";

  // The body is laid out in one buffer of known size (millions of vertices for a full-resolution
  // result), each record written in place.
  const size_t vertex_bytes = 12 + 4 * fields.size() + (coloured ? 3 : 0);
  const size_t face_bytes = 13 + 4 * face_fields.size();
  std::vector<unsigned char> body(static_cast<size_t>(mesh.vertex_count()) * vertex_bytes +
                                  static_cast<size_t>(mesh.triangle_count()) * face_bytes);
  unsigned char* at = body.data();
  const double upper_end = coloured ? coloring.upper(fields.front().values) : 0.0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) at = put_le(at, static_cast<float>(mesh.positions[v][c]));
    for (const PlyField& field : fields) at = put_le(at, static_cast<float>(field.values[v]));
    if (coloured) {
      const Rgb8 rgb = coloring.color(fields.front().values[v], upper_end);
      at = std::copy(rgb.begin(), rgb.end(), at);
    }
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    *at++ = 3;
    for (int c = 0; c < 3; ++c) at = put_le(at, static_cast<std::int32_t>(mesh.triangles[t][c]));
    for (const PlyFaceField& field : face_fields) at = put_le(at, static_cast<float>(field.values[t]));
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

void write_field_ply(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                     const FieldColoring& coloring, const std::string& property_name) {
  write_fields_ply(path, mesh, {PlyField{property_name, values}}, coloring, property_name + " per input vertex");
}

}  // namespace physarum
