// `physarum render RUN_DIR [--color_map SPEC] [--views N] [--width W] [--height H] [--out DIR]`:
// re-colours a finished run without simulating again. The values are read back from the run's own
// files (fields_full.ply, pheromone.ply), coloured through the chosen colour map and drawn from
// several views; the recoloured PLY files, texture.png and result.glb are written beside the
// pictures. The texture needs the surface itself (which intrinsic face each texel lies in): the
// surface is rebuilt from the recipe run.json records (the input mesh and the refinement keys),
// checked against fields_full.ply, and baked as `physarum run` bakes (api/run/surface_exports.hpp).
//
// Everything is read and checked before DIR is touched, and every file is written under a
// temporary name and renamed (as `physarum run` does), so a bad run folder writes nothing.
#include "common/base/atomic_write.hpp"
#include "common/output/camera_views.hpp"
#include "common/color/color_map_json.hpp"
#include "common/base/errors.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/output/ply_writer.hpp"
#include "common/output/preview_image.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/setup/scene_surface.hpp"
#include "tools/commands.hpp"
#include "api/run/surface_exports.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;

struct RenderOptions {
  std::string run_dir;
  std::string color_map;  // "" = the run's own colour map
  int views = 3;
  int width = 800;
  int height = 600;
  std::string out;  // "" = RUN_DIR/render
};

// The parts of run.json that say how the run coloured its result.
struct RunRecord {
  double U = 0.0;  // the colours' unit: U of Eq. 5 (agent runs) or run.json's color_unit (reaction-diffusion)
  std::string field = "pheromone";  // the property the pictures show: a reaction-diffusion run's preview morphogen
  ColorMapSettings color_map;  // the run's own colours (viridis 0 .. 2U for runs that did not record them)
  std::optional<SurfaceSpec> surface;      // how to rebuild the surface (runs before it was recorded: none)
  std::optional<TextureSettings> texture;  // how the run baked texture.png (none: the mesh has no UVs)
  std::string fields_file = "pheromone.ply";  // the result on the input mesh (morphogens.ply for reaction-diffusion)
};

RunRecord read_run_record(const fs::path& run_dir) {
  const fs::path path = run_dir / "run.json";
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open (is " + run_dir.string() + " a `physarum run` output folder?)");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path.string() + ": not valid JSON: " + e.what());
  }
  RunRecord r;
  const char* unit = j.contains("color_unit") ? "color_unit" : "U";
  if (!j.contains(unit) || !j[unit].is_number() || !(j[unit].get<double>() > 0.0))
    throw InputError(path.string() + ": no positive '" + unit + "' (the unit the colours are scaled to)");
  r.U = j[unit].get<double>();
  if (j.contains("preview_morphogen") && j["preview_morphogen"].is_string()) r.field = j["preview_morphogen"].get<std::string>();
  if (j.contains("colormap")) r.color_map = color_map_settings_from_json(j["colormap"], path.string() + ": key 'colormap'");
  if (j.contains("surface")) r.surface = surface_spec_from_json(j["surface"], path.string() + ": key 'surface'");
  if (j.contains("texture")) r.texture = TextureSettings::from_json(j["texture"], path.string() + ": key 'texture'");
  if (j.contains("fields_file") && j["fields_file"].is_string()) r.fields_file = j["fields_file"].get<std::string>();
  return r;
}

// --color_map: a built-in name or a colour-map file. An unknown name is a usage error (exit 2); a
// file that cannot be used is bad input (exit 1).
ColorMapSettings color_map_option(const std::string& spec) {
  const auto& names = ColorMap::names();
  if (std::find(names.begin(), names.end(), spec) != names.end()) {
    ColorMapSettings settings;
    settings.map = ColorMap::named(spec);
    return settings;
  }
  const fs::path path(spec);
  if (path.extension() != ".json" && !path.has_parent_path()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw UsageError("--colormap " + spec + ": unknown colour map (built-in: " + list + "; or give a MAP.json file)");
  }
  return read_color_map_file(spec);
}

// One result mesh of the run: its values and the file it came from.
struct ResultFile {
  std::string name;  // file name inside the run folder
  PlyFields ply;
  InputVertexData<double> values;
};

std::optional<ResultFile> read_result(const fs::path& run_dir, const std::string& name, const std::string& field) {
  const fs::path path = run_dir / name;
  if (!fs::exists(path)) return std::nullopt;
  ResultFile r{name, read_ply_fields(path.string()), {}};
  const std::vector<double>& v = r.ply.property(field);
  r.values = InputVertexData<double>(v);
  return r;
}

int run_render(const RenderOptions& o) {
  const std::vector<CameraView> views = standard_views(o.views);
  if (o.width < 1 || o.width > 16384 || o.height < 1 || o.height > 16384)
    throw UsageError("--width and --height must be between 1 and 16384");

  // ---- read everything first ----
  const fs::path run_dir(o.run_dir);
  const RunRecord run = read_run_record(run_dir);
  const std::optional<ResultFile> full = read_result(run_dir, "fields_full.ply", run.field);
  const std::optional<ResultFile> on_input = read_result(run_dir, run.fields_file, run.field);
  if (!full && !on_input) throw InputError(run_dir.string() + ": has neither fields_full.ply nor " + run.fields_file);
  // Pictures come from the finest result there is.
  const ResultFile& picture_source = full ? *full : *on_input;

  // The surface, where the run baked a texture (rebuilding is the slow part; pictures do not need it).
  std::optional<SurfaceForExports> rebuilt;
  if (run.texture) {
    if (!run.surface) throw InputError((run_dir / "run.json").string() + ": records a texture but not the surface to bake it on");
    if (!full || !on_input)
      throw InputError(run_dir.string() + ": re-baking texture.png needs both fields_full.ply and " + run.fields_file);
    rebuilt = rebuild_surface_for_exports(*run.surface, *run.texture, full->ply.mesh, (run_dir / full->name).string());
    if (rebuilt->surface.input.triangles != on_input->ply.mesh.triangles)
      throw InputError((run_dir / on_input->name).string() + " does not match the mesh " + run.surface->mesh);
  }

  // Levels are in multiples of U, as `physarum run` colours.
  const FieldColoring coloring = (o.color_map.empty() ? run.color_map : color_map_option(o.color_map)).mapping(run.U);

  // ---- write ----
  const fs::path out = o.out.empty() ? run_dir / "render" : fs::path(o.out);
  create_output_folder(out.string());
  std::string written;
  auto note = [&](const std::string& name) { written += (written.empty() ? "" : ", ") + name; };
  for (const ResultFile* r : {full ? &*full : nullptr, on_input ? &*on_input : nullptr}) {
    if (!r) continue;
    // Every field the run wrote (a reaction-diffusion run: each morphogen), the shown one first: the
    // vertex colours are the first field's, recoloured here.
    std::vector<InputVertexData<double>> others;
    std::vector<std::string> other_names;
    for (const std::string& name : r->ply.property_names)
      if (name != run.field && name != "red" && name != "green" && name != "blue" && name != "alpha")
        other_names.push_back(name), others.emplace_back(r->ply.properties.at(name));
    std::vector<PlyField> fields{PlyField{run.field, r->values}};
    for (size_t k = 0; k < others.size(); ++k) fields.push_back(PlyField{other_names[k], others[k]});
    write_fields_ply((out / r->name).string(), r->ply.mesh, fields, coloring, "recoloured by physarum render");
    note(r->name);
  }
  PreviewOptions preview;
  preview.coloring = coloring;
  preview.width = o.width;
  preview.height = o.height;
  write_preview_png((out / "preview.png").string(), picture_source.ply.mesh, picture_source.values, preview);
  note("preview.png");
  for (const CameraView& view : views) {
    preview.azimuth_deg = view.azimuth_deg;
    preview.elevation_deg = view.elevation_deg;
    const std::string name = "view_" + view.name + ".png";
    write_preview_png((out / name).string(), picture_source.ply.mesh, picture_source.values, preview);
    note(name);
  }
  // result.glb, and texture.png where the run baked one. Without a texture the glb is
  // fields_full.ply's mesh (or, for a run without one, the input mesh, which pheromone.ply is).
  if (on_input) {
    const InputMesh& mesh = rebuilt ? rebuilt->surface.input : on_input->ply.mesh;
    const SurfaceDomain empty_domain;
    const SurfaceExportsWritten exports = write_surface_exports(
        out, mesh, rebuilt ? rebuilt->surface.domain : empty_domain,
        rebuilt ? std::optional<TexelLocations>(std::move(rebuilt->texels)) : std::nullopt,
        IntrinsicVertexData<double>(full ? full->values.values() : std::vector<double>{}), on_input->values, coloring,
        run.texture.value_or(TextureSettings{}), full ? &full->ply.mesh : nullptr);
    for (const std::string& name : exports.files) note(name);
  }
  std::cout << "physarum render: " << picture_source.name << " (" << picture_source.ply.mesh.vertex_count()
            << " vertices); wrote " << out.string() << "/{" << written << "}\n";
  return 0;
}

}  // namespace

Command add_render_command(CLI::App& parent) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* app = parent.add_subcommand(
      "render",
      "Re-colour a finished run without simulating again\n"
      "Re-colour a finished run without simulating again: reads RUN_DIR/fields_full.ply (else pheromone.ply or morphogens.ply) and "
      "RUN_DIR/run.json, and writes DIR/preview.png, one DIR/view_NAME.png per view and the re-coloured PLY files. "
      "Example: physarum render out --colormap magma --views 3 --out out/magma");
  app->footer("Exit codes: 0 success, 1 bad input (a missing or malformed run folder; nothing is written), 2 usage error.");
  app->add_option("run_dir", options->run_dir, "Output folder of `physarum run`")->required();
  std::string names;
  for (const std::string& n : ColorMap::names()) names += (names.empty() ? "" : ", ") + n;
  app->add_option("--colormap", options->color_map,
                  "Colour map: a built-in name (" + names + ") or a MAP.json file (default: the run's own, from run.json)");
  app->add_option("--views", options->views,
                  "1: the preview's three-quarter view; 3: front, side and top; other N: a turntable of N frames")
      ->capture_default_str();
  app->add_option("--width", options->width, "Picture width in pixels")->capture_default_str();
  app->add_option("--height", options->height, "Picture height in pixels")->capture_default_str();
  app->add_option("--out", options->out, "Output folder (default: RUN_DIR/render)");
  return Command{app, [options] { return run_render(*options); }};
}

}  // namespace physarum::cli
