#pragma once
// The outputs of a run that need the surface itself, not only the values on a mesh: the field baked
// onto the input's UVs (texture.png, and texture.exr on request) and result.glb, which embeds that
// texture (or, without UVs, is the full-resolution mesh). `physarum run` writes them after
// simulating; `physarum render` writes them again with other colours, rebuilding the surface from
// what run.json records (so both go through this one function and a re-coloured texture is made
// exactly as the run's was).
#include "common/color/color_mapping.hpp"
#include "common/base/element_data.hpp"
#include "common/output/gltf_writer.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/output/texture_bake.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// --texture-size, --texture-margin, --texture-format of `physarum run`, as run.json records them.
struct TextureSettings {
  int size = 2048;             // texels per side
  int margin = 16;             // seam padding in texels
  std::string format = "png";  // png (8-bit), png16, exr (texture.png and texture.exr)

  // UsageError naming the flag when a value is out of range.
  void check() const;
  nlohmann::ordered_json to_json() const;
  // InputError naming `where` when a key is missing or out of range.
  static TextureSettings from_json(const nlohmann::json& j, const std::string& where);
};

// The surface's recipe as run.json records it ("surface"): the mesh as an absolute path (or the
// shape:NAME spec), so `physarum render` finds it from any working directory, and the scaling and
// refinement keys. Rebuilding from it gives the same triangulation (prepare_surface is
// deterministic); render checks that against fields_full.ply.
nlohmann::ordered_json surface_spec_json(const SurfaceSpec& spec);
// InputError naming `where` when a key is missing or has the wrong type.
SurfaceSpec surface_spec_from_json(const nlohmann::json& j, const std::string& where);

// Where each texel of a --texture-size square lies on the triangulation, found before a run starts:
// a UV map that cannot be baked is bad input, refused before anything is simulated or written. Without
// UVs: nothing, and `note` tells the user that no texture.png will be written.
std::optional<TexelLocations> texels_for_run(const InputMesh& input, const SurfaceDomain& domain,
                                             const TextureSettings& texture, const SurfaceNote& note);

struct SurfaceExportsWritten {
  std::vector<std::string> files;  // names inside the output folder, in the order written
  GltfExportSummary glb;
};

// Writes into `out`: texture.png (and texture.exr) when `texels` are given (the input has UVs),
// then result.glb: with a texture, the input mesh with `on_input` (the field on the input's vertices)
// as its values and vertex colours; without, `full_mesh` (fields_full.ply's mesh, whose vertex v is
// intrinsic vertex v) with `field` (on the intrinsic vertices: the texture samples it too) as its
// values and colours, or the input mesh again when `full_mesh` is null (a run folder from before
// fields_full.ply). Both are coloured by `coloring` as pheromone.ply and fields_full.ply are.
SurfaceExportsWritten write_surface_exports(const std::filesystem::path& out, const InputMesh& input,
                                            const SurfaceDomain& domain, const std::optional<TexelLocations>& texels,
                                            const IntrinsicVertexData<double>& field,
                                            const InputVertexData<double>& on_input, const ColorMapping& coloring,
                                            const TextureSettings& texture, const InputMesh* full_mesh);

// A composite of several fields (a two-layer sketch's colour sets, common/color/layer_colours.hpp): as
// write_surface_exports, with `fields` (on the intrinsic vertices) baked together and each texel
// coloured by `texel_colour` from its channel values, result.glb's vertex colours `vertex_colours`
// and its values `on_input` on `input` — the caller passes the full-resolution mesh and its values
// when there are no texels; texture.png is 8-bit whatever the format (texture.exr still on request).
SurfaceExportsWritten write_composed_exports(const std::filesystem::path& out, const InputMesh& input,
                                             const SurfaceDomain& domain, const std::optional<TexelLocations>& texels,
                                             const std::vector<BakeField>& fields,
                                             const std::function<SrgbColor(const float* channels)>& texel_colour,
                                             const InputVertexData<double>& on_input,
                                             const InputVertexData<Rgb8>& vertex_colours, const TextureSettings& texture);

// The surface rebuilt from the recipe run.json records must be the one the run simulated on: the
// same intrinsic triangles, its vertices where `recorded` (fields_full.ply's mesh, read from `file`)
// has them, to the PLY's float precision. InputError naming `file` and `mesh` otherwise.
void check_same_triangulation(const InputMesh& rebuilt, const InputMesh& recorded, const std::string& file,
                              const std::string& mesh);

// What re-baking a finished run's texture needs: its surface and where each texel lies on it.
struct SurfaceForExports {
  PreparedSurface surface;
  TexelLocations texels;
};

// Rebuilds the surface from run.json's recipe (the slow part: the intrinsic refinement), checks it
// against the run's fields_full.ply (check_same_triangulation) and locates the texels at the run's
// texture size.
SurfaceForExports rebuild_surface_for_exports(const SurfaceSpec& spec, const TextureSettings& texture,
                                              const InputMesh& recorded_full, const std::string& full_file);

}  // namespace physarum
