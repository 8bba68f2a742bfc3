#pragma once
// result.glb read back through tinygltf's own loader, for tests of what the writer put there
// (tests/test_gltf_writer.cpp) and of the files commands write (tests/test_cli_sketch.cpp).
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace physarum::testing {

// The sRGB decoding curve (IEC 61966-2-1), written out here rather than taken from the writer.
inline double expected_linear(std::uint8_t byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

struct LoadedGlb {
  tinygltf::Model model;
  std::vector<std::vector<unsigned char>> image_bytes;  // the encoded images, as stored
};

// Loads through tinygltf's binary loader; images are kept encoded (the build has no stb).
inline LoadedGlb load_glb(const std::string& path) {
  LoadedGlb glb;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(
      [](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char* bytes, int size,
         void* user) {
        static_cast<LoadedGlb*>(user)->image_bytes.emplace_back(bytes, bytes + size);
        return true;
      },
      &glb);
  std::string error, warning;
  const bool ok = loader.LoadBinaryFromFile(&glb.model, &error, &warning, path);
  EXPECT_TRUE(ok) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  return glb;
}

// The floats of a tightly packed float accessor, `components` per element, checked for type.
inline std::vector<float> read_floats(const tinygltf::Model& m, int accessor_index, int type, int components) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<size_t>(accessor_index));
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(a.type, type);
  EXPECT_FALSE(a.normalized);
  const tinygltf::BufferView& view = m.bufferViews.at(static_cast<size_t>(a.bufferView));
  EXPECT_EQ(view.target, TINYGLTF_TARGET_ARRAY_BUFFER);
  EXPECT_TRUE(view.byteStride == 0 || view.byteStride == sizeof(float) * static_cast<size_t>(components));
  const size_t n = a.count * static_cast<size_t>(components);
  EXPECT_LE(a.byteOffset + n * sizeof(float), view.byteLength);
  std::vector<float> out(n);
  std::memcpy(out.data(), m.buffers.at(static_cast<size_t>(view.buffer)).data.data() + view.byteOffset + a.byteOffset,
              n * sizeof(float));
  return out;
}

}  // namespace physarum::testing
