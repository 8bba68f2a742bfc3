#include "api/run/surface_exports.hpp"

#include "common/base/errors.hpp"
#include "common/output/preview_image.hpp"
#include "common/output/texture_image.hpp"
#include "common/surface/full_resolution_mesh.hpp"

#include <algorithm>


namespace physarum {

void TextureSettings::check() const {
  if (size < 1 || size > TexelLocations::kMaxSize)
    throw UsageError("--texture-size " + std::to_string(size) + " must be between 1 and " +
                     std::to_string(TexelLocations::kMaxSize));
  if (margin < 0) throw UsageError("--texture-margin " + std::to_string(margin) + " must be >= 0");
  if (format != "png" && format != "png16" && format != "exr")
    throw UsageError("--texture-format " + format + " must be png, png16 or exr");
}

nlohmann::ordered_json TextureSettings::to_json() const {
  nlohmann::ordered_json j;
  j["size"] = size;
  j["margin"] = margin;
  j["format"] = format;
  return j;
}

TextureSettings TextureSettings::from_json(const nlohmann::json& j, const std::string& where) {
  TextureSettings t;
  try {
    t.size = j.at("size").get<int>();
    t.margin = j.at("margin").get<int>();
    t.format = j.at("format").get<std::string>();
    t.check();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where + ": needs size, margin and format: " + e.what());
  } catch (const UsageError& e) {
    throw InputError(where + ": " + e.what());
  }
  return t;
}

nlohmann::ordered_json surface_spec_json(const SurfaceSpec& spec) {
  nlohmann::ordered_json j;
  const bool shape = spec.mesh.rfind("shape:", 0) == 0;
  j["mesh"] = shape ? spec.mesh : std::filesystem::absolute(spec.mesh).lexically_normal().string();
  j["scale_to_area"] = spec.scale_to_area ? nlohmann::ordered_json(*spec.scale_to_area) : nlohmann::ordered_json();
  j["max_circumradius"] =
      spec.max_circumradius ? nlohmann::ordered_json(*spec.max_circumradius) : nlohmann::ordered_json();
  j["min_angle"] = spec.min_angle_deg;
  return j;
}

SurfaceSpec surface_spec_from_json(const nlohmann::json& j, const std::string& where) {
  SurfaceSpec spec;
  try {
    spec.mesh = j.at("mesh").get<std::string>();
    if (!j.at("scale_to_area").is_null()) spec.scale_to_area = j.at("scale_to_area").get<double>();
    if (!j.at("max_circumradius").is_null()) spec.max_circumradius = j.at("max_circumradius").get<double>();
    spec.min_angle_deg = j.at("min_angle").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where + ": needs mesh, scale_to_area, max_circumradius and min_angle: " + e.what());
  }
  return spec;
}

namespace {

// texture.exr on request: the baked channels' raw values.
void write_exr_if_asked(const std::filesystem::path& out, const BakedTexture& baked, const TextureSettings& texture,
                        SurfaceExportsWritten& written) {
  if (texture.format != "exr") return;
  write_texture_exr((out / "texture.exr").string(), baked);
  written.files.push_back("texture.exr");
}

}  // namespace

SurfaceExportsWritten write_surface_exports(const std::filesystem::path& out, const InputMesh& input,
                                            const SurfaceDomain& domain, const std::optional<TexelLocations>& texels,
                                            const IntrinsicVertexData<double>& field,
                                            const InputVertexData<double>& on_input, const ColorMapping& coloring,
                                            const TextureSettings& texture, const InputMesh* full_mesh) {
  SurfaceExportsWritten written;
  std::optional<GltfTexture> glb_texture;
  if (texels) {
    const BakedTexture baked = bake_fields(*texels, domain, {BakeField{"pheromone", field}}, BakeOptions{.margin = texture.margin});
    TextureColouring colouring;
    colouring.coloring = coloring;
    // The top of the colour map as in fields_full.ply, whose vertex values are `field`'s.
    colouring.upper_end = coloring.upper(InputVertexData<double>(field.values()));
    write_texture_png((out / "texture.png").string(), baked, 0, colouring, texture.format == "png16" ? 16 : 8);
    written.files.push_back("texture.png");
    glb_texture = GltfTexture{baked.width, baked.height, texture_rgb8(baked, 0, colouring)};
    write_exr_if_asked(out, baked, texture, written);
  }
  // result.glb keeps the run's whole detail in any viewer. With UVs: the input mesh and the baked
  // texture, which carries the detail between its vertices. Without: the full-resolution mesh (every
  // intrinsic vertex on the input surface, fields_full.ply's mesh) with its colours and values — the
  // input's vertex colours alone would show triangle-sized blotches where the run resolved strands
  // (a generated chart atlas would need a parametrization of arbitrary meshes, and resample the
  // field once more). The colours are the PLYs' (the same map over the same range).
  auto colours_of = [&](const InputVertexData<double>& values) {
    InputVertexData<Rgb8> colors(values.size());
    const double upper_end = coloring.upper(values);
    for (size_t v = 0; v < values.size(); ++v) colors[v] = coloring.color(values[v], upper_end);
    return colors;
  };
  const std::string glb = (out / "result.glb").string();
  if (glb_texture || !full_mesh) {
    written.glb = write_result_glb(glb, input, on_input, colours_of(on_input), glb_texture);
  } else {
    const InputVertexData<double> on_full(field.values());
    written.glb = write_result_glb(glb, *full_mesh, on_full, colours_of(on_full), std::nullopt);
  }
  written.files.push_back("result.glb");
  return written;
}

SurfaceExportsWritten write_composed_exports(const std::filesystem::path& out, const InputMesh& input,
                                             const SurfaceDomain& domain, const std::optional<TexelLocations>& texels,
                                             const std::vector<BakeField>& fields,
                                             const std::function<SrgbColor(const float* channels)>& texel_colour,
                                             const InputVertexData<double>& on_input,
                                             const InputVertexData<Rgb8>& vertex_colours, const TextureSettings& texture) {
  SurfaceExportsWritten written;
  std::optional<GltfTexture> glb_texture;
  if (texels) {
    const BakedTexture baked = bake_fields(*texels, domain, fields, BakeOptions{.margin = texture.margin});
    RgbImage image{baked.width, baked.height, composed_texture_rgb8(baked, texel_colour)};
    write_rgb_png((out / "texture.png").string(), image);
    written.files.push_back("texture.png");
    glb_texture = GltfTexture{baked.width, baked.height, std::move(image.pixels)};
    write_exr_if_asked(out, baked, texture, written);
  }
  written.glb = write_result_glb((out / "result.glb").string(), input, on_input, vertex_colours, glb_texture);
  written.files.push_back("result.glb");
  return written;
}

void check_same_triangulation(const InputMesh& rebuilt, const InputMesh& recorded, const std::string& file,
                              const std::string& mesh) {
  const std::string why = file + " does not match the surface rebuilt from " + mesh + " (was the mesh file changed "
                          "since the run?): ";
  if (rebuilt.vertex_count() != recorded.vertex_count() || rebuilt.triangle_count() != recorded.triangle_count())
    throw InputError(why + std::to_string(recorded.vertex_count()) + " vertices and " +
                     std::to_string(recorded.triangle_count()) + " triangles recorded, " +
                     std::to_string(rebuilt.vertex_count()) + " and " + std::to_string(rebuilt.triangle_count()) +
                     " rebuilt");
  if (rebuilt.triangles != recorded.triangles) throw InputError(why + "the triangles differ");
  double extent = 0.0;
  for (const Eigen::Vector3d& p : rebuilt.positions) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  for (int v = 0; v < rebuilt.vertex_count(); ++v)
    if ((rebuilt.positions[static_cast<size_t>(v)] - recorded.positions[static_cast<size_t>(v)]).cwiseAbs().maxCoeff() >
        1e-6 * std::max(extent, 1e-30))
      throw InputError(why + "vertex " + std::to_string(v) + " moved");
}

SurfaceForExports rebuild_surface_for_exports(const SurfaceSpec& spec, const TextureSettings& texture,
                                              const InputMesh& recorded_full, const std::string& full_file) {
  PreparedSurface surface = prepare_surface(spec);
  check_same_triangulation(build_full_resolution_mesh(surface.input, surface.domain).mesh, recorded_full, full_file, spec.mesh);
  TexelLocations texels = locate_texels(surface.input, surface.domain, texture.size, texture.size);
  return SurfaceForExports{std::move(surface), std::move(texels)};
}

std::optional<TexelLocations> texels_for_run(const InputMesh& input, const SurfaceDomain& domain,
                                             const TextureSettings& texture, const SurfaceNote& note) {
  if (!input.uvs.empty()) return locate_texels(input, domain, texture.size, texture.size);
  if (note) note("physarum run: note: " + input.source + " has no texture coordinates (UVs); no texture.png is written");
  return std::nullopt;
}

}  // namespace physarum
