#include "api/sketch/sketch_colours.hpp"

#include "common/base/errors.hpp"
#include "common/color/layer_colours.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/output/camera_views.hpp"
#include "common/output/preview_image.hpp"
#include "api/run/surface_exports.hpp"
#include "api/sketch/sketch_layers.hpp"

#include <fstream>

namespace physarum {
namespace {

namespace fs = std::filesystem;

// One layer's field at full resolution (fields_full.ply) and on the input vertices (morphogens.ply).
struct LayerFields {
  PlyFields full, on_input;
};

LayerFields read_layer(const fs::path& folder) {
  return {read_ply_fields((folder / "fields_full.ply").string()), read_ply_fields((folder / "morphogens.ply").string())};
}

// The first layer's share of each vertex: 1 in its frozen spots (frozen_vertices, as the cascade
// froze them), 0 elsewhere; 1 everywhere for a single layer.
std::vector<double> first_share(const std::vector<double>& first, const std::optional<FirstLayerColours>& layer) {
  if (!layer) return std::vector<double>(first.size(), 1.0);
  const std::vector<char> frozen = frozen_vertices(first, layer->threshold);
  return std::vector<double>(frozen.begin(), frozen.end());
}

}  // namespace

std::vector<ColorMapSettings> read_colour_sets(const std::vector<std::string>& specs) {
  if (specs.size() > 2) throw UsageError("--colors takes one set per layer: one or two, not " + std::to_string(specs.size()));
  std::vector<ColorMapSettings> sets;
  for (size_t k = 0; k < specs.size(); ++k)
    sets.push_back(resolve_color_map(specs[k], fs::current_path().string(), "--colors set " + std::to_string(k + 1)));
  return sets;
}

std::vector<std::string> write_layer_colours(const fs::path& folder, const std::string& field, const ColorMapSettings& set,
                                             const std::optional<FirstLayerColours>& first,
                                             const ColorMapSettings& first_set) {
  // ---- read ----
  const LayerFields last = read_layer(folder);
  const std::optional<LayerFields> below = first ? std::optional<LayerFields>(read_layer(first->folder)) : std::nullopt;
  const LayerFields& lowest = below ? *below : last;
  // Per vertex, at full resolution and on the input: the first layer's field, the final field and
  // the first layer's share (a single layer: its field twice, share 1).
  const InputVertexData<double> first_full(lowest.full.property(field)), last_full(last.full.property(field)),
      share_full(first_share(first_full.values(), first));
  const std::vector<double>&first_on_input = lowest.on_input.property(field), &last_on_input = last.on_input.property(field);
  const std::vector<double> share_on_input = first_share(first_on_input, first);
  const LayerColours colours = first ? LayerColours(first_set, first_full.values(), set, last_full.values(), share_full.values())
                                     : LayerColours(set, last_full.values());
  const fs::path run_json = folder / "run.json";
  std::ifstream in(run_json);
  const nlohmann::json record = nlohmann::json::parse(in, nullptr, false);
  if (record.is_discarded() || !record.contains("surface")) throw InputError(run_json.string() + ": no surface recorded");
  std::optional<SurfaceForExports> rebuilt;
  TextureSettings texture;
  if (record.contains("texture")) {
    texture = TextureSettings::from_json(record["texture"], run_json.string() + ": key 'texture'");
    rebuilt = rebuild_surface_for_exports(surface_spec_from_json(record["surface"], run_json.string() + ": key 'surface'"),
                                          texture, last.full.mesh, (folder / "fields_full.ply").string());
  }

  // ---- write ----
  std::vector<std::string> written;
  for (const CameraView& view : {preview_view(), standard_views(3).front()}) {
    PreviewOptions options;
    options.azimuth_deg = view.azimuth_deg;
    options.elevation_deg = view.elevation_deg;
    const std::string name = view.name == preview_view().name ? "preview.png" : "view_" + view.name + ".png";
    write_rgb_png((folder / name).string(),
                  render_layers_preview(last.full.mesh, first_full, last_full, share_full, colours, options));
    written.push_back(name);
  }
  // result.glb as a run's (surface_exports.hpp): the input mesh and the baked texture where there are
  // UVs, else the full-resolution mesh with its own colours, so a viewer shows every resolved detail.
  const bool textured = rebuilt.has_value();
  const std::vector<double>& glb_first = textured ? first_on_input : first_full.values();
  const std::vector<double>& glb_last = textured ? last_on_input : last_full.values();
  const std::vector<double>& glb_share = textured ? share_on_input : share_full.values();
  InputVertexData<Rgb8> vertex_colours(glb_last.size());
  for (size_t v = 0; v < glb_last.size(); ++v) vertex_colours[v] = to_rgb8(colours.at(glb_first[v], glb_last[v], glb_share[v]));
  const IntrinsicVertexData<double> first_i(first_full.values()), last_i(last_full.values()), share_i(share_full.values());
  const SurfaceDomain no_domain;
  const SurfaceExportsWritten exports = write_composed_exports(
      folder, textured ? rebuilt->surface.input : last.full.mesh, textured ? rebuilt->surface.domain : no_domain,
      textured ? std::optional<TexelLocations>(std::move(rebuilt->texels)) : std::nullopt,
      {BakeField{"first", first_i}, BakeField{"last", last_i}, BakeField{"first_share", share_i}},
      [&](const float* c) { return colours.at(c[0], c[1], c[2]); }, InputVertexData<double>(glb_last), vertex_colours,
      texture);
  written.insert(written.end(), exports.files.begin(), exports.files.end());
  return written;
}

}  // namespace physarum
