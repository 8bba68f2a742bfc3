// result.glb read back through tinygltf's own loader: counts and accessor types as the glTF 2.0
// specification wants them, colours linear by an sRGB transfer function computed here, the V flip
// of the texture coordinates, vertices split exactly where a vertex has several UVs, the embedded
// PNG (its size read from the PNG header by hand, its pixels through OpenImageIO), and failed
// writes that leave no file.
#include "common/base/errors.hpp"
#include "common/output/gltf_writer.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "glb_reader.hpp"
#include "pheromone_test_meshes.hpp"
#include "test_support.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <utility>

namespace physarum {
namespace {

using testing::expected_linear;
using testing::LoadedGlb;
using testing::load_glb;
using testing::read_floats;
using testing::TempDir;

std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& m, int accessor_index) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<size_t>(accessor_index));
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  EXPECT_EQ(a.type, TINYGLTF_TYPE_SCALAR);
  const tinygltf::BufferView& view = m.bufferViews.at(static_cast<size_t>(a.bufferView));
  EXPECT_EQ(view.target, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  std::vector<std::uint32_t> out(a.count);
  std::memcpy(out.data(), m.buffers.at(0).data.data() + view.byteOffset + a.byteOffset, a.count * 4);
  return out;
}

// Field values and colours that differ from vertex to vertex, covering dark bytes (the linear part
// of the curve, below 0.04045 * 255 = 10.3), mid-tones and the ends.
InputVertexData<double> some_values(const InputMesh& mesh) {
  InputVertexData<double> v(mesh.positions.size());
  for (size_t i = 0; i < v.size(); ++i) v[i] = 0.25 + 1.5 * static_cast<double>(i);
  return v;
}
InputVertexData<Rgb8> some_colors(const InputMesh& mesh) {
  InputVertexData<Rgb8> c(mesh.positions.size());
  for (size_t i = 0; i < c.size(); ++i)
    c[i] = {static_cast<std::uint8_t>((37 * i) % 256), static_cast<std::uint8_t>((5 * i + 3) % 256),
            static_cast<std::uint8_t>(255 - (11 * i) % 256)};
  if (!c.empty()) c[0] = {0, 128, 255};
  return c;
}

// Every triangle corner of the file must be the input corner it came from: same position, same
// value, and (u, 1 - v) of that corner's UV. Also the first V file vertices are the input's, in order.
void expect_corners_match_input(const tinygltf::Model& m, const InputMesh& mesh, const InputVertexData<double>& values) {
  const tinygltf::Primitive& p = m.meshes.at(0).primitives.at(0);
  const auto position = read_floats(m, p.attributes.at("POSITION"), TINYGLTF_TYPE_VEC3, 3);
  const auto value = read_floats(m, p.attributes.at("_PHEROMONE"), TINYGLTF_TYPE_SCALAR, 1);
  const auto index = read_indices(m, p.indices);
  const bool has_uvs = !mesh.triangle_uvs.empty();
  std::vector<float> uv;
  if (has_uvs) uv = read_floats(m, p.attributes.at("TEXCOORD_0"), TINYGLTF_TYPE_VEC2, 2);
  ASSERT_EQ(index.size(), 3 * mesh.triangles.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      const size_t file_vertex = index[3 * f + static_cast<size_t>(c)];
      const auto v = static_cast<size_t>(mesh.triangles[f][c]);
      ASSERT_LT(file_vertex, value.size());
      for (int k = 0; k < 3; ++k) ASSERT_EQ(position[3 * file_vertex + static_cast<size_t>(k)], static_cast<float>(mesh.positions[v][k]));
      ASSERT_EQ(value[file_vertex], static_cast<float>(values[v]));
      if (has_uvs) {
        const Eigen::Vector2d& t = mesh.uvs[static_cast<size_t>(mesh.triangle_uvs[f][c])];
        ASSERT_EQ(uv[2 * file_vertex], static_cast<float>(t.x())) << "triangle " << f << " corner " << c;
        ASSERT_EQ(uv[2 * file_vertex + 1], static_cast<float>(1.0 - t.y())) << "V not flipped, triangle " << f;
      }
    }
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(position[3 * v + static_cast<size_t>(k)], static_cast<float>(mesh.positions[v][k]));
}

// (vertex, uv index) pairs the faces use: the vertex count a one-UV-per-vertex format needs.
size_t distinct_vertex_uv_pairs(const InputMesh& mesh) {
  std::set<std::pair<int, int>> pairs;
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) pairs.insert({mesh.triangles[f][c], mesh.triangle_uvs[f][c]});
  return pairs.size();
}

TEST(SrgbToLinear, KnownValues) {
  EXPECT_EQ(srgb_to_linear(0.0), 0.0);
  EXPECT_NEAR(srgb_to_linear(1.0), 1.0, 1e-15);
  EXPECT_NEAR(srgb_to_linear(0.5), 0.21404, 5e-6);  // the textbook mid-grey
  EXPECT_NEAR(srgb_to_linear(0.04045), 0.0031308, 1e-7);  // where the two pieces meet
  EXPECT_NEAR(srgb_to_linear(0.02), 0.02 / 12.92, 1e-15);
}

// A sphere without UVs: one TRIANGLES primitive, input vertices and triangles unchanged, POSITION's
// bounds, unit normals that point outwards, linear COLOR_0, the raw values, the material.
TEST(GltfWriter, UntexturedMeshRoundTrip) {
  const InputMesh mesh = testing::make_icosphere(2);
  const auto values = some_values(mesh);
  const auto colors = some_colors(mesh);
  TempDir dir;
  const std::string path = (dir.path / "result.glb").string();
  const GltfExportSummary summary = write_result_glb(path, mesh, values, colors);
  EXPECT_EQ(summary.vertices, mesh.vertex_count());
  EXPECT_EQ(summary.seam_splits, 0);
  EXPECT_FALSE(summary.has_uvs);
  EXPECT_FALSE(summary.textured);
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"result.glb"}) << "temporary file left behind";

  const LoadedGlb glb = load_glb(path);
  const tinygltf::Model& m = glb.model;
  EXPECT_EQ(m.asset.version, "2.0");
  ASSERT_EQ(m.meshes.size(), 1u);
  ASSERT_EQ(m.meshes[0].primitives.size(), 1u);
  ASSERT_EQ(m.scenes.size(), 1u);
  ASSERT_EQ(m.nodes.size(), 1u);
  EXPECT_EQ(m.nodes[0].mesh, 0);
  const tinygltf::Primitive& p = m.meshes[0].primitives[0];
  EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
  EXPECT_EQ(p.attributes.count("TEXCOORD_0"), 0u);
  EXPECT_EQ(p.attributes.count("_FIELD_COLOR"), 0u);
  for (const char* name : {"POSITION", "NORMAL", "COLOR_0", "_PHEROMONE"}) {
    ASSERT_EQ(p.attributes.count(name), 1u) << name;
    EXPECT_EQ(m.accessors[static_cast<size_t>(p.attributes.at(name))].count, mesh.positions.size()) << name;
  }
  expect_corners_match_input(m, mesh, values);
  const auto index = read_indices(m, p.indices);
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(index[3 * f + static_cast<size_t>(c)], static_cast<std::uint32_t>(mesh.triangles[f][c]));

  // POSITION's min/max: the bounds of the stored floats (the unit icosphere: -1 .. 1 on every axis).
  const tinygltf::Accessor& pa = m.accessors[static_cast<size_t>(p.attributes.at("POSITION"))];
  ASSERT_EQ(pa.minValues.size(), 3u);
  ASSERT_EQ(pa.maxValues.size(), 3u);
  const auto position = read_floats(m, p.attributes.at("POSITION"), TINYGLTF_TYPE_VEC3, 3);
  for (int k = 0; k < 3; ++k) {
    float lo = position[static_cast<size_t>(k)], hi = lo;
    for (size_t i = static_cast<size_t>(k); i < position.size(); i += 3) lo = std::min(lo, position[i]), hi = std::max(hi, position[i]);
    EXPECT_EQ(pa.minValues[static_cast<size_t>(k)], lo);
    EXPECT_EQ(pa.maxValues[static_cast<size_t>(k)], hi);
    EXPECT_NEAR(lo, -1.0, 0.05);
    EXPECT_NEAR(hi, 1.0, 0.05);
  }
  // On a sphere centred at the origin the area-weighted normal is nearly radial, and unit length.
  const auto normal = read_floats(m, p.attributes.at("NORMAL"), TINYGLTF_TYPE_VEC3, 3);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d n(normal[3 * v], normal[3 * v + 1], normal[3 * v + 2]);
    ASSERT_NEAR(n.norm(), 1.0, 1e-6);
    ASSERT_GT(n.dot(mesh.positions[v].normalized()), 0.99) << "vertex " << v;
  }
  // COLOR_0 is linear: each sRGB byte through the transfer function.
  const auto color = read_floats(m, p.attributes.at("COLOR_0"), TINYGLTF_TYPE_VEC3, 3);
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (size_t k = 0; k < 3; ++k) ASSERT_NEAR(color[3 * v + k], expected_linear(colors[v][k]), 1e-6) << "vertex " << v;
  EXPECT_EQ(color[0], 0.0f);
  EXPECT_NEAR(color[1], 0.21586, 1e-5);  // byte 128 = 0.50196 in sRGB
  EXPECT_EQ(color[2], 1.0f);

  ASSERT_EQ(m.materials.size(), 1u);
  const tinygltf::Material& mat = m.materials[0];
  EXPECT_EQ(p.material, 0);
  EXPECT_TRUE(mat.doubleSided);
  EXPECT_EQ(mat.pbrMetallicRoughness.metallicFactor, 0.0);
  EXPECT_NEAR(mat.pbrMetallicRoughness.roughnessFactor, 0.8, 1e-12);
  EXPECT_EQ(mat.pbrMetallicRoughness.baseColorFactor, (std::vector<double>{1, 1, 1, 1}));
  EXPECT_EQ(mat.pbrMetallicRoughness.baseColorTexture.index, -1);
  EXPECT_TRUE(m.images.empty());
}

// Two triangles of a square cut apart in UV space along their shared diagonal: vertices 0 and 2 have
// two UVs each, so the file holds 4 + 2 vertices; every corner keeps its own UV, flipped in V.
InputMesh seam_square() {
  InputMesh mesh;
  mesh.source = "seam square";
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.uvs = {{0.0, 0.0}, {0.5, 0.0}, {0.5, 0.5}, {0.6, 0.1}, {1.0, 0.6}, {0.6, 0.6}};
  mesh.triangle_uvs = {{0, 1, 2}, {3, 4, 5}};
  mesh.file_vertex = {0, 1, 2, 3};
  return mesh;
}

TEST(GltfWriter, UvSeamSplitsVerticesAndFlipsV) {
  const InputMesh mesh = seam_square();
  const auto values = some_values(mesh);
  TempDir dir;
  const std::string path = (dir.path / "result.glb").string();
  const GltfExportSummary summary = write_result_glb(path, mesh, values, some_colors(mesh));
  EXPECT_EQ(summary.seam_splits, 2);
  EXPECT_EQ(summary.vertices, 6);
  EXPECT_TRUE(summary.has_uvs);
  const LoadedGlb glb = load_glb(path);
  const tinygltf::Primitive& p = glb.model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(glb.model.accessors[static_cast<size_t>(p.attributes.at("POSITION"))].count, 6u);
  expect_corners_match_input(glb.model, mesh, values);
  // A copy has the same normal as its original: shading is smooth across the seam.
  const auto normal = read_floats(glb.model, p.attributes.at("NORMAL"), TINYGLTF_TYPE_VEC3, 3);
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(normal[3 * i + 2], 1.0f, 1e-6);  // the square faces +z
}

// spot.obj (real UV seams): exactly one file vertex per distinct (vertex, uv) pair.
TEST(GltfWriter, SpotSeamSplitCountIsDistinctVertexUvPairs) {
  PHYSARUM_REQUIRE_SHARED_MESH(spot, "spot.obj");
  const InputMesh mesh = load_mesh(spot);
  ASSERT_FALSE(mesh.triangle_uvs.empty());
  const auto values = some_values(mesh);
  TempDir dir;
  const std::string path = (dir.path / "result.glb").string();
  const GltfExportSummary summary = write_result_glb(path, mesh, values, some_colors(mesh));
  const size_t pairs = distinct_vertex_uv_pairs(mesh);
  EXPECT_GT(pairs, mesh.positions.size()) << "spot.obj has seams";
  EXPECT_EQ(static_cast<size_t>(summary.vertices), pairs);
  EXPECT_EQ(static_cast<size_t>(summary.seam_splits), pairs - mesh.positions.size());
  const LoadedGlb glb = load_glb(path);
  const tinygltf::Primitive& p = glb.model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(glb.model.accessors[static_cast<size_t>(p.attributes.at("POSITION"))].count, pairs);
  expect_corners_match_input(glb.model, mesh, values);
}

// With a texture: the PNG is in the binary chunk (bufferView, image/png, no URI), its size and
// pixels are the texture's, the sampler is trilinear with clamped edges, the material uses it, and
// the colours move from COLOR_0 to _FIELD_COLOR (a viewer would multiply the texture by COLOR_0).
TEST(GltfWriter, TextureIsEmbeddedPngAndReplacesColor0) {
  const InputMesh mesh = seam_square();
  const auto colors = some_colors(mesh);
  GltfTexture texture;
  texture.width = 5;
  texture.height = 3;
  for (int i = 0; i < 5 * 3 * 3; ++i) texture.pixels.push_back(static_cast<std::uint8_t>(17 * i + 1));
  TempDir dir;
  const std::string path = (dir.path / "result.glb").string();
  const GltfExportSummary summary = write_result_glb(path, mesh, some_values(mesh), colors, texture);
  EXPECT_TRUE(summary.textured);
  const LoadedGlb glb = load_glb(path);
  const tinygltf::Model& m = glb.model;
  const tinygltf::Primitive& p = m.meshes.at(0).primitives.at(0);
  EXPECT_EQ(p.attributes.count("COLOR_0"), 0u);
  ASSERT_EQ(p.attributes.count("_FIELD_COLOR"), 1u);
  ASSERT_EQ(p.attributes.count("TEXCOORD_0"), 1u);
  const auto color = read_floats(m, p.attributes.at("_FIELD_COLOR"), TINYGLTF_TYPE_VEC3, 3);
  for (size_t i = 0; i < 6; ++i) {  // copies carry their original's colour
    const size_t v = i < 4 ? i : (i == 4 ? 0 : 2);
    for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(color[3 * i + k], expected_linear(colors[v][k]), 1e-6) << i;
  }

  const tinygltf::Material& mat = m.materials.at(0);
  ASSERT_EQ(mat.pbrMetallicRoughness.baseColorTexture.index, 0);
  EXPECT_EQ(mat.pbrMetallicRoughness.baseColorTexture.texCoord, 0);
  EXPECT_EQ(mat.pbrMetallicRoughness.baseColorFactor, (std::vector<double>{1, 1, 1, 1}));
  ASSERT_EQ(m.textures.size(), 1u);
  ASSERT_EQ(m.textures[0].source, 0);
  ASSERT_EQ(m.textures[0].sampler, 0);
  const tinygltf::Sampler& s = m.samplers.at(0);
  EXPECT_EQ(s.minFilter, TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR);
  EXPECT_EQ(s.magFilter, TINYGLTF_TEXTURE_FILTER_LINEAR);
  EXPECT_EQ(s.wrapS, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE);
  EXPECT_EQ(s.wrapT, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE);
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.images[0].mimeType, "image/png");
  EXPECT_TRUE(m.images[0].uri.empty());
  EXPECT_GE(m.images[0].bufferView, 0);

  // The PNG's own header: signature, then IHDR with big-endian width and height.
  ASSERT_EQ(glb.image_bytes.size(), 1u);
  const std::vector<unsigned char>& png = glb.image_bytes[0];
  ASSERT_GE(png.size(), 24u);
  EXPECT_EQ(std::memcmp(png.data(), "\x89PNG\r\n\x1a\n", 8), 0);
  EXPECT_EQ(std::memcmp(png.data() + 12, "IHDR", 4), 0);
  auto be32 = [&](size_t at) { return (png[at] << 24) | (png[at + 1] << 16) | (png[at + 2] << 8) | png[at + 3]; };
  EXPECT_EQ(be32(16), 5);
  EXPECT_EQ(be32(20), 3);
  // The pixels, lossless, top row first.
  OIIO::Filesystem::IOMemReader reader(png.data(), png.size());
  auto in = OIIO::ImageInput::create("png");
  ASSERT_TRUE(in);
  ASSERT_TRUE(in->set_ioproxy(&reader));
  OIIO::ImageSpec spec;
  ASSERT_TRUE(in->open("texture.png", spec)) << in->geterror();
  ASSERT_EQ(in->spec().nchannels, 3);
  std::vector<std::uint8_t> pixels(5 * 3 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixels.data()));
  EXPECT_EQ(pixels, texture.pixels);
}

// UVs beyond [0, 1] are baked where their wrapped value lies, so the sampler must repeat there;
// an atlas inside [0, 1] keeps clamping (checked above).
TEST(GltfWriter, TiledUvsGetARepeatingSampler) {
  InputMesh mesh = seam_square();
  for (Eigen::Vector2d& uv : mesh.uvs) uv.x() += 1.0;  // the same chart, one tile to the right
  GltfTexture texture{2, 2, std::vector<std::uint8_t>(12, 128)};
  TempDir dir;
  const std::string path = (dir.path / "result.glb").string();
  write_result_glb(path, mesh, some_values(mesh), some_colors(mesh), texture);
  const tinygltf::Sampler& s = load_glb(path).model.samplers.at(0);
  EXPECT_EQ(s.wrapS, TINYGLTF_TEXTURE_WRAP_REPEAT);
  EXPECT_EQ(s.wrapT, TINYGLTF_TEXTURE_WRAP_REPEAT);
}

// Bad requests throw InputError naming the path and leave nothing behind.
TEST(GltfWriter, FailuresLeaveNoFile) {
  const InputMesh sphere = testing::make_icosphere(1);
  const InputMesh square = seam_square();
  TempDir dir;
  const std::string path = (dir.path / "result.glb").string();
  auto expect_input_error = [&](auto&& write) {
    try {
      write();
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_TRUE(files_in(dir.path).empty());
  };
  // Sizes that do not match the mesh.
  expect_input_error([&] { write_result_glb(path, sphere, InputVertexData<double>{1.0}, some_colors(sphere)); });
  expect_input_error([&] { write_result_glb(path, sphere, some_values(sphere), InputVertexData<Rgb8>(3)); });
  // A texture on a mesh without UVs, and a texture whose pixels do not fill it.
  GltfTexture texture{2, 2, std::vector<std::uint8_t>(12, 200)};
  expect_input_error([&] { write_result_glb(path, sphere, some_values(sphere), some_colors(sphere), texture); });
  texture.pixels.resize(11);
  expect_input_error([&] { write_result_glb(path, square, some_values(square), some_colors(square), texture); });
  // The target is a folder: writing succeeds, the rename fails, the temporary file goes.
  std::filesystem::create_directory(path);
  try {
    write_result_glb(path, sphere, some_values(sphere), some_colors(sphere));
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"result.glb"});
  EXPECT_TRUE(std::filesystem::is_directory(path));
  // A folder that does not exist.
  const std::string missing = (dir.path / "no" / "result.glb").string();
  EXPECT_THROW(write_result_glb(missing, sphere, some_values(sphere), some_colors(sphere)), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.path / "no"));
}

}  // namespace
}  // namespace physarum
