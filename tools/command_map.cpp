// `physarum map`: surface maps written onto the INPUT mesh, so a user can look at what a simulation
// would see (MeshLab, Blender, the preview PNG) before running it. Two forms:
//   physarum map SCENE.json [--out maps.ply]     every named map of a scene (key 'maps')
//   physarum map MESH --kind KIND [--value V] [--arg KEY=VALUE ...] [--maps HELPERS.json] [--name N]
//                [--scale-to-area A] [--max-circumradius R | --max-circumradius-rel F] [--min-angle D]
//                [--out N.ply]                   one map on a mesh file or shape:NAME
// Scalar maps become vertex properties of their names, vector maps face properties NAME_x, NAME_y,
// NAME_z in input coordinates. Each map also gets a picture (common/output/map_preview.hpp): FILE.png beside
// the PLY for one map, FILE_NAME.png per map for a scene.
//
// One map is built as JSON and goes through the scene's own parser (parse_maps), so every source
// kind the map table knows works here without code of its own: --kind names the source's defining
// key, --value its value ({"axis": "z"}), and each --arg adds a field. A plain KEY goes into the
// kind's object when the kind's value is an object (no --value, or an object value):
// {"geodesic_distance": {"from": ..., "method": "fmm"}}; beside the kind when --value is not an
// object: {"diffuse": "seed", "time": 0.01}. A KEY starting with '/' is a JSON pointer from the map's
// own object, for a field beside the kind's object: --arg /falloff=0.1.
//
// Maps go through the on-disk map cache (common/setup/cached_map_evaluation.hpp). For a scene, the
// parameters and controls that use the maps are evaluated too, so a map value out of a parameter's
// range is refused here as `run` would.
#include "common/output/maps_ply.hpp"
#include "common/setup/cached_map_evaluation.hpp"
#include "common/base/errors.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/output/map_preview.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/setup/scene_surface.hpp"
#include "tools/commands.hpp"
#include "tools/refinement_options.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct MapOptions {
  std::string input;  // SCENE.json, a mesh file or shape:NAME
  std::string out;    // default: maps.ply (scene) or NAME.ply (one map)
  std::string preview;
  bool no_preview = false;
  int width = 800, height = 600;
  // one map on a mesh
  std::string kind, value, name, maps_file;
  std::vector<std::string> args;
  std::optional<double> scale_to_area;
  RefinementFlags refinement;
};

bool is_scene_file(const std::string& input) {
  std::string extension = fs::path(input).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension == ".json";
}

// A command-line value: JSON when it parses as JSON, else the text itself. Text that starts like a
// JSON object, array or string but does not parse is refused: it is almost surely a typo.
json json_or_text(const std::string& text, const std::string& what) {
  json value = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!value.is_discarded()) return value;
  const size_t first = text.find_first_not_of(" \t");
  if (first != std::string::npos && (text[first] == '{' || text[first] == '[' || text[first] == '"')) {
    try {
      const json parsed = json::parse(text);  // throws: parsing failed above; this says where
    } catch (const json::parse_error& e) {
      throw UsageError(what + ": not valid JSON: " + e.what());
    }
  }
  return text;
}

// The map's definition from --kind, --value and --arg (see the header comment).
json definition_from_options(const MapOptions& o) {
  json definition = json::object();
  const bool value_given = !o.value.empty();
  json kind_value = value_given ? json_or_text(o.value, "--value " + o.value) : json::object();
  const bool args_inside = kind_value.is_object();
  definition[o.kind] = kind_value;
  std::set<std::string> seen;
  for (const std::string& arg : o.args) {
    const size_t equals = arg.find('=');
    if (equals == std::string::npos)
      throw UsageError("--arg " + arg + ": expected KEY=VALUE (e.g. --arg method=fmm, --arg 'center=[0,0,1]')");
    const std::string key = arg.substr(0, equals);
    if (key.empty() || key == "/") throw UsageError("--arg " + arg + ": the key before '=' is empty");
    const json value = json_or_text(arg.substr(equals + 1), "--arg " + arg);
    std::string pointer;
    if (key.front() == '/') {
      pointer = key;
    } else {
      if (key.find('/') != std::string::npos || key.find('~') != std::string::npos)
        throw UsageError("--arg " + arg + ": a plain KEY holds no '/' or '~' (start it with '/' for a JSON pointer)");
      pointer = args_inside ? "/" + o.kind + "/" + key : "/" + key;
    }
    if (pointer == "/" + o.kind)
      throw UsageError("--arg " + arg + ": sets the kind's own value; give it with --value");
    if (!seen.insert(pointer).second) throw UsageError("--arg " + arg + ": " + pointer + " is given twice");
    try {
      const json::json_pointer at(pointer);
      if (!definition.contains(at.parent_pointer()) || !definition[at.parent_pointer()].is_object())
        throw UsageError("--arg " + arg + ": " + pointer.substr(0, pointer.rfind('/')) +
                         " is not an object of fields" + (args_inside ? "" : " (--value gave the kind a plain value, so plain keys go beside it)"));
      definition[at] = value;
    } catch (const json::exception& e) {
      throw UsageError("--arg " + arg + ": " + e.what());
    }
  }
  return definition;
}

// The helper maps of --maps: a JSON object of named maps, like a scene's "maps".
json helper_maps(const std::string& path) {
  if (path.empty()) return json::object();
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the --maps file");
  json maps;
  try {
    maps = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(path + ": not valid JSON: " + e.what());
  }
  if (!maps.is_object())
    throw InputError(path + ": --maps must hold a JSON object of named maps ({\"NAME\": SOURCE, ...}), like a scene's \"maps\"");
  return maps;
}

std::string preview_path_for(const MapOptions& o, const std::string& out, const std::string& map_name, bool one_map) {
  const fs::path stem = o.preview.empty() ? fs::path(out).replace_extension("") : fs::path(o.preview).replace_extension("");
  if (one_map) return stem.string() + ".png";
  return stem.string() + "_" + map_name + ".png";
}

void print_report(const MapEvaluationReport& report) {
  for (const std::string& note : report.notes) std::cerr << "physarum map: " << note << "\n";
  std::cerr << "physarum map: " << report.summary() << "\n";
}

// Writes the PLY and the pictures of `maps` on `surface` (one picture FILE.png for `one_map`, else
// FILE_NAME.png per map, even when a scene has a single map); prints one line per map.
void write_maps(const MapOptions& o, const std::string& out, const MapSet& maps, const PreparedSurface& surface,
                const EvaluatedMaps& evaluated, const std::string& where, bool one_map) {
  const InputMaps on_input = maps_on_input(maps, surface, evaluated, where);
  // Pictures first: rendering can fail on a bad size, and then nothing should have been written.
  std::vector<std::pair<std::string, RgbImage>> pictures;
  if (!o.no_preview) {
    MapPreviewOptions view;
    view.width = o.width;
    view.height = o.height;
    std::optional<FullResolutionMesh> full;
    for (const auto& [name, values] : on_input.scalar) {
      (void)values;
      if (!full) full = build_full_resolution_mesh(surface.input, surface.domain);
      pictures.emplace_back(preview_path_for(o, out, name, one_map),
                            render_scalar_map_preview(full->mesh, full->vertex_values(evaluated.scalar_map(name)), name, view));
    }
    for (const auto& [name, vectors] : on_input.vector)
      pictures.emplace_back(preview_path_for(o, out, name, one_map), render_vector_map_preview(surface.input, vectors, name, view));
  }
  // Every file's folder must exist before the first is written: a bad --preview leaves no PLY behind.
  std::vector<std::string> targets{out};
  for (const auto& picture : pictures) targets.push_back(picture.first);
  for (const std::string& target : targets) {
    const fs::path folder = fs::path(target).has_parent_path() ? fs::path(target).parent_path() : fs::path(".");
    if (!fs::is_directory(folder)) throw InputError(target + ": cannot write: folder " + folder.string() + " does not exist");
  }
  write_maps_ply(out, surface.input, on_input);
  for (const auto& [path, image] : pictures) write_rgb_png(path, image);

  for (const auto& [name, values] : on_input.scalar) {
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    std::printf("%-20s scalar  min %-12.6g max %-12.6g (on %d input vertices)\n", name.c_str(), *low, *high,
                surface.input.vertex_count());
  }
  for (const auto& [name, vectors] : on_input.vector) {
    double shortest = vectors.empty() ? 0.0 : vectors.front().norm(), longest = shortest;
    for (const auto& v : vectors) shortest = std::min(shortest, v.norm()), longest = std::max(longest, v.norm());
    std::printf("%-20s vector  length %.6g .. %.6g (on %d input faces)\n", name.c_str(), shortest, longest,
                surface.input.triangle_count());
  }
  std::printf("surface              %d input vertices; intrinsic triangulation %d vertices, %d faces\n",
              surface.input.vertex_count(), surface.domain.vertex_count, surface.domain.face_count);
  std::printf("physarum map: wrote %s", out.c_str());
  for (const auto& picture : pictures) std::printf(", %s", picture.first.c_str());
  std::printf("\n");
}

int run_scene_maps(const MapOptions& o) {
  const Scene scene = load_scene(o.input);
  if (scene.maps.empty()) throw InputError(o.input + ": key 'maps': the scene defines no maps");
  const PreparedSurface surface = prepare_scene_surface(scene, [](const std::string& line) { std::cerr << line << "\n"; });
  for (const std::string& w : surface.warnings) std::cerr << "physarum: warning: " << w << "\n";
  MapEvaluationReport report;
  const EvaluatedMaps maps = cached_evaluate_maps(map_sources_of(scene), surface, MapCache::from_environment(), &report);
  print_report(report);
  // The same checks as `run`: parameter values in range, spawn weights usable.
  vertex_parameters(scene, surface, maps);
  simulation_controls(scene, surface, maps);
  write_maps(o, o.out.empty() ? "maps.ply" : o.out, scene.maps, surface, maps, o.input, /*one_map=*/false);
  return 0;
}

int run_one_map(const MapOptions& o) {
  const std::string name = o.name.empty() ? o.kind : o.name;
  json maps = helper_maps(o.maps_file);
  if (maps.contains(name))
    throw UsageError("--maps " + o.maps_file + " already defines a map '" + name + "'; name this one with --name");
  maps[name] = definition_from_options(o);
  const std::string folder = o.maps_file.empty() ? std::string(".") : fs::path(o.maps_file).parent_path().string();
  const std::string where = o.maps_file.empty() ? "physarum map --kind " + o.kind : o.maps_file + " (with --kind " + o.kind + ")";
  const MapSet parsed = parse_maps(maps, folder.empty() ? "." : folder, where);
  // Only the new map and what it reads are evaluated and written, not every helper.
  std::set<std::string> needed;
  std::vector<std::string> pending{name};
  while (!pending.empty()) {
    const std::string next = pending.back();
    pending.pop_back();
    if (!needed.insert(next).second) continue;
    for (const std::string& d : parsed.find(next)->dependencies()) pending.push_back(d);
  }
  std::vector<MapDefinition> wanted;
  for (const MapDefinition& m : parsed.in_dependency_order())
    if (needed.count(m.name)) wanted.push_back(m);
  const MapSet evaluated_set(std::move(wanted));

  SurfaceSpec spec;
  spec.mesh = o.input;
  spec.scale_to_area = o.scale_to_area;
  spec.min_angle_deg = o.refinement.min_angle_deg;
  InputMesh input = load_mesh(o.input);
  {
    // A fraction of the bounding-box diagonal of the surface as simulated (after --scale-to-area).
    const InputMeshStatistics statistics = compute_statistics(input);
    const double scale = o.scale_to_area ? std::sqrt(*o.scale_to_area / statistics.area) : 1.0;
    spec.max_circumradius = o.refinement.absolute_max_circumradius(statistics.bounding_box_diagonal * scale);
  }
  const PreparedSurface surface = prepare_surface(std::move(input), spec, [](const std::string& line) { std::cerr << line << "\n"; });
  for (const std::string& w : surface.warnings) std::cerr << "physarum: warning: " << w << "\n";

  MapEvaluationReport report;
  const EvaluatedMaps evaluated =
      cached_evaluate_maps(MapSources{evaluated_set, maps, folder.empty() ? "." : folder, spec, where}, surface,
                           MapCache::from_environment(), &report);
  print_report(report);
  // Write the asked-for map alone: helpers it reads are inputs, not results.
  const MapSet only(std::vector<MapDefinition>{*parsed.find(name)});
  write_maps(o, o.out.empty() ? name + ".ply" : o.out, only, surface, evaluated, where, /*one_map=*/true);
  return 0;
}

int run_map(const MapOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    throw UsageError("--width and --height must be in 1..16384");
  if (is_scene_file(o.input)) {
    std::vector<std::string> mesh_only;
    if (!o.kind.empty()) mesh_only.push_back("--kind");
    if (!o.value.empty()) mesh_only.push_back("--value");
    if (!o.args.empty()) mesh_only.push_back("--arg");
    if (!o.maps_file.empty()) mesh_only.push_back("--maps");
    if (!o.name.empty()) mesh_only.push_back("--name");
    if (o.scale_to_area || o.refinement.any())
      mesh_only.push_back("the surface options");
    if (!mesh_only.empty()) {
      std::string list;
      for (const std::string& m : mesh_only) list += (list.empty() ? "" : ", ") + m;
      throw UsageError(o.input + " is a scene: its maps and surface come from the file, so " + list +
                       " (one map on a MESH) cannot be used with it");
    }
    return run_scene_maps(o);
  }
  if (o.kind.empty())
    throw UsageError("physarum map " + o.input + ": a mesh needs --kind KIND (the map to compute on it), or give a scene file (.json)");
  return run_one_map(o);
}

}  // namespace

Command add_map_command(CLI::App& parent) {
  auto options = std::make_shared<MapOptions>();
  CLI::App* app = parent.add_subcommand(
      "map",
      "Evaluate surface maps on the intrinsic triangulation and write them onto the input mesh\n"
      "Evaluate surface maps on the intrinsic triangulation and write them onto the input mesh as a PLY (scalar maps "
      "per vertex under their names, vector maps per face as NAME_x, NAME_y, NAME_z in input coordinates) with a "
      "preview picture per map. Given a scene: every named map (key 'maps'). Given a mesh file or shape:NAME: one "
      "map, built from --kind, --value and --arg as the JSON a scene would hold.");
  app->footer(
      "One map on a mesh (--kind is the source's key; --value its value; --arg KEY=VALUE a field, VALUE as JSON or "
      "plain text; a plain KEY goes into the kind's object unless --value gave the kind a plain value, a /KEY is a "
      "JSON pointer from the map's own object):\n"
      "  physarum map shape:sphere --kind axis --value y --out ramp.ply\n"
      "  physarum map shape:disk --kind sphere --arg 'center=[0,0,0]' --arg radius=0.3 --arg /falloff=0.2\n"
      "  physarum map spot.obj --kind geodesic_distance --arg 'from={\"points\":[[0,0,1]]}' --arg method=fmm\n"
      "  physarum map spot.obj --maps seeds.json --kind diffuse --value seed --arg time=0.01 --max-circumradius-rel 0.01\n"
      "  physarum map shape:torus --kind direction --value '[1,0,0]' --name east\n"
      "Every map of a scene, with pictures maps_NAME.png:\n"
      "  physarum map tools/scenes/sign.json --out maps.ply\n"
      "Maps are cached in $PHYSARUM_CACHE_DIR, else $XDG_CACHE_HOME/physarum, else ~/.cache/physarum "
      "(PHYSARUM_NO_CACHE=1: off; PHYSARUM_CACHE_MAX_MB: size budget, default 2048).\n"
      "Exit codes: 0 success, 1 bad input (nothing is written), 2 usage error.");
  app->add_option("input", options->input, "A scene file (.json) with a 'maps' key, or a mesh (OBJ, OFF, PLY, STL) or shape:NAME")
      ->required();
  app->add_option("--out", options->out, "The PLY file to write (its folder must exist); default maps.ply for a scene, NAME.ply for one map");
  app->add_option("--preview", options->preview,
                  "The picture: this file for one map; for a scene its stem, as STEM_NAME.png per map (default: beside --out)");
  app->add_flag("--no-preview", options->no_preview, "Write no picture");
  app->add_option("--width", options->width, "Picture width in pixels")->capture_default_str();
  app->add_option("--height", options->height, "Picture height in pixels, the legend band included")->capture_default_str();
  app->add_option("--kind", options->kind, "One map on a mesh: the source's key (axis, sphere, direction, ply, geodesic_distance, ...)");
  app->add_option("--value", options->value, "The value of the kind's key: JSON or plain text (--kind axis --value z)");
  // One value per --arg, so a positional argument after it is not taken as another field.
  app->add_option("--arg", options->args, "KEY=VALUE: a field of the map (repeatable; see below)")->allow_extra_args(false);
  app->add_option("--maps", options->maps_file,
                  "A JSON file of named helper maps the kind reads ({\"NAME\": SOURCE, ...}, like a scene's 'maps'); relative "
                  "file names in it and in --value/--arg resolve against its folder");
  app->add_option("--name", options->name, "The property name of the one map (default: the kind)");
  app->add_option("--scale-to-area", options->scale_to_area, "Rescale the mesh to this area first (as a scene's scale_to_area)")
      ->check(CLI::PositiveNumber);
  add_refinement_flags(app, options->refinement, "Refine until no intrinsic face has a larger circumradius (after --scale-to-area)");
  return {app, [options] { return run_map(*options); }};
}

}  // namespace physarum::cli
