#pragma once
// The result as a glTF 2.0 binary (`result.glb`), the format every 3D viewer, game engine and web
// page opens: the INPUT mesh with smooth normals, the field's colours, its raw values, and — where
// the mesh has texture coordinates and a baked texture is given — that texture as the material's
// base colour. Built with tinygltf and written through a temporary file and rename
// (atomic_write.hpp).
//
// What is in the file (one scene, one node, one mesh, one TRIANGLES primitive, one material):
//   POSITION    float VEC3, the input coordinates, with the min/max the specification requires;
//   NORMAL      float VEC3, area-weighted vertex normals (the sum of the incident faces' cross
//               products), so viewers shade the surface smoothly, across UV seams too;
//   TEXCOORD_0  float VEC2, only where the mesh has UVs: (u, 1 - v), because glTF puts v = 0 at the
//               TOP of the image and OBJ at the bottom;
//   COLOR_0     float VEC3, the field's colours in LINEAR RGB (glTF vertex colours are linear; the
//               sRGB bytes of pheromone.ply go through the exact sRGB transfer function);
//   _PHEROMONE  float SCALAR, the field's value per vertex (an application-specific attribute, as
//               the specification allows for names starting with '_'), so the data survives;
//   indices     uint32.
// The material is white, metallic 0, roughness 0.8 and double-sided (surfaces may be open).
//
// With a texture, the colours move from COLOR_0 to the custom attribute _FIELD_COLOR (the same
// linear values): a viewer MULTIPLIES baseColorTexture by COLOR_0 (glTF 2.0, "Metallic-Roughness
// Material"), so keeping both would show the colour map applied twice (darker, hue-shifted), and the
// texture — baked from the full-resolution field, finer than the input's vertices — alone is the
// right look. The colours stay in the file, only under a name viewers do not multiply by.
// The texture is an sRGB PNG (glTF samples baseColorTexture as sRGB) embedded in the binary chunk,
// sampled with trilinear filtering (LINEAR_MIPMAP_LINEAR, LINEAR) and CLAMP_TO_EDGE wrapping: a baked
// atlas lies inside [0, 1]², and REPEAT would blend the opposite border of the atlas into charts
// that touch an edge. A mesh whose UVs leave [0, 1] (tiled UVs, which the bake wraps) gets REPEAT.
//
// glTF has one UV per vertex, while the input may give a vertex different UVs on different faces (a
// seam): such a vertex is written once per distinct UV index. The first V vertices of the file are
// the input's vertices in order (each with the UV of the first face that uses it); the copies
// follow, so a reader maps file vertex i < V to input vertex i.
#include "common/color/color_map.hpp"
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// A baked texture: 8-bit sRGB RGB, row-major, TOP row first (row 0 is glTF's v = 0 and OBJ's v = 1).
struct GltfTexture {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3 bytes
};

// What was written, for the run's report and for readers that check the file.
struct GltfExportSummary {
  int vertices = 0;        // vertices in the file = input vertices + seam_splits
  int triangles = 0;
  int seam_splits = 0;     // extra copies of vertices that carry several UVs
  bool has_uvs = false;    // TEXCOORD_0 written
  bool textured = false;   // baseColorTexture written (then the colours are in _FIELD_COLOR, not COLOR_0)
};

// sRGB-encoded value in [0, 1] to linear light, the exact piecewise sRGB transfer function
// (IEC 61966-2-1): c / 12.92 up to 0.04045, ((c + 0.055) / 1.055)^2.4 above.
double srgb_to_linear(double c);

// Writes `mesh` to `path` as glTF 2.0 binary. `values` and `colors` (sRGB, as in pheromone.ply) hold
// one entry per input vertex. `texture` needs the mesh's UVs. Throws InputError naming `path` on a
// size mismatch, a texture without UVs or with a wrong pixel count, or a failed write; then no
// file, not even a partial one, is left at `path`.
GltfExportSummary write_result_glb(const std::string& path, const InputMesh& mesh, const InputVertexData<double>& values,
                                   const InputVertexData<Rgb8>& colors,
                                   const std::optional<GltfTexture>& texture = std::nullopt);

}  // namespace physarum
