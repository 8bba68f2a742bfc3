// The one translation unit that compiles tinygltf (Debian ships it as a header). Its stb-based image
// code is off (TINYGLTF_NO_STB_IMAGE, _WRITE, NO_EXTERNAL_IMAGE, set on the physarum_output target
// so that every file including tiny_gltf.h sees the same configuration): the texture is encoded to
// PNG here through OpenImageIO, and the file never refers to an image outside itself.
#include "common/output/gltf_writer.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <utility>

namespace physarum {
namespace {

// glTF constants (the specification's numeric enums).
constexpr int kArrayBuffer = TINYGLTF_TARGET_ARRAY_BUFFER;                  // 34962
constexpr int kElementArrayBuffer = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;  // 34963

// The vertices of the file: each (input vertex, UV index) pair once. Input vertex v keeps index v
// (with the first UV it is seen with); further UVs of v get copies appended at the end.
struct VertexLayout {
  std::vector<int> source;  // file vertex -> input vertex
  std::vector<int> uv;      // file vertex -> UV index (empty without UVs)
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

VertexLayout split_uv_seams(const InputMesh& mesh) {
  VertexLayout layout;
  const int n = mesh.vertex_count();
  layout.source.resize(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v) layout.source[static_cast<size_t>(v)] = v;
  layout.triangles.reserve(mesh.triangles.size());
  if (mesh.triangle_uvs.empty()) {
    for (const auto& t : mesh.triangles)
      layout.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                                  static_cast<std::uint32_t>(t[2])});
    return layout;
  }
  layout.uv.assign(static_cast<size_t>(n), -1);
  std::map<std::pair<int, int>, int> copies;  // (input vertex, uv index) -> appended file vertex
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    std::array<std::uint32_t, 3> out{};
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.triangles[f][c];
      const int uv = mesh.triangle_uvs[f][c];
      int index = v;
      if (layout.uv[static_cast<size_t>(v)] == -1) {
        layout.uv[static_cast<size_t>(v)] = uv;
      } else if (layout.uv[static_cast<size_t>(v)] != uv) {
        const auto [it, inserted] = copies.try_emplace({v, uv}, static_cast<int>(layout.source.size()));
        if (inserted) {
          layout.source.push_back(v);
          layout.uv.push_back(uv);
        }
        index = it->second;
      }
      out[c] = static_cast<std::uint32_t>(index);
    }
    layout.triangles.push_back(out);
  }
  // A vertex no face uses has no UV; (0, 0) is as good as any.
  for (int& uv : layout.uv)
    if (uv == -1) uv = 0;
  return layout;
}

// Area-weighted normals: the sum of the incident faces' (unnormalised) cross products, whose length
// is twice the face's area. A vertex whose faces cancel or are degenerate gets +z (glTF requires
// unit normals).
std::vector<Eigen::Vector3d> area_weighted_normals(const InputMesh& mesh) {
  std::vector<Eigen::Vector3d> normals(mesh.positions.size(), Eigen::Vector3d::Zero());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[static_cast<size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.positions[static_cast<size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.positions[static_cast<size_t>(t[2])];
    const Eigen::Vector3d face = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normals[static_cast<size_t>(t[k])] += face;
  }
  for (auto& n : normals) {
    const double length = n.norm();
    n = length > 0.0 && std::isfinite(length) ? Eigen::Vector3d(n / length) : Eigen::Vector3d::UnitZ();
  }
  return normals;
}

// The binary chunk, built one buffer view at a time; every view starts on a 4-byte boundary (the
// specification requires accessor offsets to be multiples of the component size).
class BinaryChunk {
 public:
  explicit BinaryChunk(tinygltf::Model& model) : model_(model) {}

  // Appends `bytes` as a new buffer view (target 0: none, as for an image) and returns its index.
  int add_view(const void* bytes, size_t size, int target) {
    auto& data = model_.buffers[0].data;
    while (data.size() % 4 != 0) data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = size;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(bytes);
    data.insert(data.end(), p, p + size);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  // A tightly packed float accessor over a new vertex buffer view (`components` floats per vertex).
  int add_float_attribute(const std::vector<float>& values, int components, int type) {
    tinygltf::Accessor accessor;
    accessor.bufferView = add_view(values.data(), values.size() * sizeof(float), kArrayBuffer);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.count = values.size() / static_cast<size_t>(components);
    accessor.type = type;
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

 private:
  tinygltf::Model& model_;
};

// The texture as PNG bytes, encoded in memory through OpenImageIO.
std::vector<unsigned char> encode_png(const std::string& path, const GltfTexture& texture) {
  std::vector<unsigned char> png;
  OIIO::Filesystem::IOVecOutput proxy(png);
  auto out = OIIO::ImageOutput::create("png");
  if (!out) throw InputError(path + ": cannot encode the texture: OpenImageIO has no PNG writer (" + OIIO::geterror() + ")");
  OIIO::ImageSpec spec(texture.width, texture.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  const bool ok = out->set_ioproxy(&proxy) && out->open("texture.png", spec) &&
                  out->write_image(OIIO::TypeDesc::UINT8, texture.pixels.data()) && out->close();
  if (!ok) throw InputError(path + ": cannot encode the texture as PNG: " + out->geterror());
  return png;
}

void check_inputs(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                  const InputVertexData<Rgb8>& colors, const std::optional<GltfTexture>& texture) {
  const size_t n = static_cast<size_t>(mesh.vertex_count());
  if (values.size() != n || colors.size() != n)
    throw InputError(path + ": cannot write " + std::to_string(values.size()) + " values and " +
                     std::to_string(colors.size()) + " colours onto the " + std::to_string(n) + " vertices of " +
                     mesh.source);
  if (!mesh.triangle_uvs.empty()) {
    if (mesh.triangle_uvs.size() != mesh.triangles.size())
      throw InputError(path + ": " + mesh.source + " has UVs for " + std::to_string(mesh.triangle_uvs.size()) +
                       " of its " + std::to_string(mesh.triangles.size()) + " triangles");
    for (size_t f = 0; f < mesh.triangle_uvs.size(); ++f)
      for (int uv : mesh.triangle_uvs[f])
        if (uv < 0 || static_cast<size_t>(uv) >= mesh.uvs.size())
          throw InputError(path + ": " + mesh.source + " triangle " + std::to_string(f) + " uses UV " +
                           std::to_string(uv) + " of " + std::to_string(mesh.uvs.size()));
  }
  if (texture) {
    if (mesh.triangle_uvs.empty())
      throw InputError(path + ": a texture needs texture coordinates, and " + mesh.source + " has none");
    if (texture->width < 1 || texture->height < 1 ||
        texture->pixels.size() != static_cast<size_t>(texture->width) * static_cast<size_t>(texture->height) * 3)
      throw InputError(path + ": the texture is " + std::to_string(texture->width) + "x" +
                       std::to_string(texture->height) + " but holds " + std::to_string(texture->pixels.size()) +
                       " bytes (3 per pixel expected)");
  }
}

}  // namespace

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

namespace {

// The per-vertex arrays of the file, in file order (one vertex per seam copy).
struct FileVertexArrays {
  std::vector<float> position, normal, uv, color, value;
};

FileVertexArrays file_vertex_arrays(const InputMesh& mesh, const VertexLayout& layout,
                                    const InputVertexData<double>& values, const InputVertexData<Rgb8>& colors) {
  const std::vector<Eigen::Vector3d> normals = area_weighted_normals(mesh);
  const size_t count = layout.source.size();
  FileVertexArrays a;
  a.position.reserve(3 * count);
  a.normal.reserve(3 * count);
  a.color.reserve(3 * count);
  a.value.reserve(count);
  std::array<double, 256> linear{};  // the 256 possible bytes, converted once
  for (int b = 0; b < 256; ++b) linear[static_cast<size_t>(b)] = srgb_to_linear(b / 255.0);
  for (size_t i = 0; i < count; ++i) {
    const auto v = static_cast<size_t>(layout.source[i]);
    for (int c = 0; c < 3; ++c) {
      a.position.push_back(static_cast<float>(mesh.positions[v][c]));
      a.normal.push_back(static_cast<float>(normals[v][c]));
      a.color.push_back(static_cast<float>(linear[colors[v][static_cast<size_t>(c)]]));
    }
    a.value.push_back(static_cast<float>(values[v]));
    if (!layout.uv.empty()) {
      const Eigen::Vector2d& t = mesh.uvs[static_cast<size_t>(layout.uv[i])];
      a.uv.push_back(static_cast<float>(t.x()));
      a.uv.push_back(static_cast<float>(1.0 - t.y()));  // glTF: v = 0 is the top of the image
    }
  }
  return a;
}

// The specification requires POSITION's bounds, of the float values as stored.
void set_position_bounds(tinygltf::Accessor& a, const std::vector<float>& position) {
  a.minValues.assign(3, std::numeric_limits<double>::infinity());
  a.maxValues.assign(3, -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < position.size(); ++i) {
    a.minValues[i % 3] = std::min<double>(a.minValues[i % 3], position[i]);
    a.maxValues[i % 3] = std::max<double>(a.maxValues[i % 3], position[i]);
  }
  if (position.empty()) {
    a.minValues.assign(3, 0.0);
    a.maxValues.assign(3, 0.0);
  }
}

// The triangles' vertex indices as the primitive's index accessor; returns its index.
int add_indices(tinygltf::Model& model, BinaryChunk& chunk, const VertexLayout& layout) {
  tinygltf::Accessor indices;
  indices.bufferView = chunk.add_view(layout.triangles.data(), layout.triangles.size() * sizeof(layout.triangles[0]),
                                      kElementArrayBuffer);
  indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  indices.count = 3 * layout.triangles.size();
  indices.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(indices);
  return static_cast<int>(model.accessors.size()) - 1;
}

// The baked texture as the base colour of `material`: the PNG in the binary chunk, its sampler.
void add_texture(tinygltf::Model& model, BinaryChunk& chunk, tinygltf::Material& material, const std::string& path,
                 const InputMesh& mesh, const GltfTexture& texture) {
  const std::vector<unsigned char> png = encode_png(path, texture);
  tinygltf::Image image;
  image.name = "field";
  image.mimeType = "image/png";
  image.bufferView = chunk.add_view(png.data(), png.size(), 0);
  model.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  // A UV outside [0, 1] was baked where its wrapped value lies (texture_bake.hpp), so such a mesh
  // needs REPEAT to find it; an atlas inside [0, 1] keeps CLAMP_TO_EDGE (see the header).
  const bool tiled = std::any_of(mesh.uvs.begin(), mesh.uvs.end(), [](const Eigen::Vector2d& t) {
    return t.x() < 0.0 || t.x() > 1.0 || t.y() < 0.0 || t.y() > 1.0;
  });
  sampler.wrapS = tiled ? TINYGLTF_TEXTURE_WRAP_REPEAT : TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  sampler.wrapT = sampler.wrapS;
  model.samplers.push_back(sampler);
  tinygltf::Texture gltf_texture;
  gltf_texture.source = 0;
  gltf_texture.sampler = 0;
  model.textures.push_back(gltf_texture);
  material.pbrMetallicRoughness.baseColorTexture.index = 0;
  material.pbrMetallicRoughness.baseColorTexture.texCoord = 0;
}

// One mesh of one primitive in one node of the default scene.
void add_scene(tinygltf::Model& model, const tinygltf::Primitive& primitive) {
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "result";
  gltf_mesh.primitives.push_back(primitive);
  model.meshes.push_back(gltf_mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "result";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
}

void write_glb(const std::string& path, tinygltf::Model& model) {
  write_file_atomically(path, [&](const std::string& temporary) {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (!file) throw InputError(path + ": cannot write: " + std::strerror(errno));
    tinygltf::TinyGLTF writer;
    // tinygltf does not check its stream writes; the stream's state after flushing does.
    const bool ok = writer.WriteGltfSceneToStream(&model, file, /*prettyPrint=*/false, /*writeBinary=*/true);
    file.flush();
    if (!ok || !file) throw InputError(path + ": cannot write: " + std::strerror(errno));
    file.close();
    if (!file) throw InputError(path + ": cannot write: " + std::strerror(errno));
  });
}

}  // namespace

GltfExportSummary write_result_glb(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                                   const InputVertexData<Rgb8>& colors, const std::optional<GltfTexture>& texture) {
  check_inputs(path, mesh, values, colors, texture);
  const VertexLayout layout = split_uv_seams(mesh);
  const FileVertexArrays a = file_vertex_arrays(mesh, layout, values, colors);
  const size_t count = layout.source.size();
  const bool has_uvs = !layout.uv.empty();

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "physarum";
  model.buffers.emplace_back();
  BinaryChunk chunk(model);

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = chunk.add_float_attribute(a.position, 3, TINYGLTF_TYPE_VEC3);
  set_position_bounds(model.accessors[static_cast<size_t>(primitive.attributes["POSITION"])], a.position);
  primitive.attributes["NORMAL"] = chunk.add_float_attribute(a.normal, 3, TINYGLTF_TYPE_VEC3);
  if (has_uvs) primitive.attributes["TEXCOORD_0"] = chunk.add_float_attribute(a.uv, 2, TINYGLTF_TYPE_VEC2);
  // See the header: with a texture, viewers would multiply it by COLOR_0.
  primitive.attributes[texture ? "_FIELD_COLOR" : "COLOR_0"] = chunk.add_float_attribute(a.color, 3, TINYGLTF_TYPE_VEC3);
  primitive.attributes["_PHEROMONE"] = chunk.add_float_attribute(a.value, 1, TINYGLTF_TYPE_SCALAR);
  primitive.indices = add_indices(model, chunk, layout);

  tinygltf::Material material;
  material.name = "physarum";
  material.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.8;
  material.doubleSided = true;  // open surfaces show their back faces
  if (texture) add_texture(model, chunk, material, path, mesh, *texture);
  model.materials.push_back(material);
  primitive.material = 0;
  add_scene(model, primitive);
  write_glb(path, model);

  GltfExportSummary summary;
  summary.vertices = static_cast<int>(count);
  summary.triangles = mesh.triangle_count();
  summary.seam_splits = static_cast<int>(count) - mesh.vertex_count();
  summary.has_uvs = has_uvs;
  summary.textured = texture.has_value();
  return summary;
}

}  // namespace physarum
