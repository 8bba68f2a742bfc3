// `physarum map SCENE.json --out maps.ply`: evaluate a scene's named maps (key 'maps') on its surface
// and write them onto the INPUT mesh, so a user can look at what a simulation would see (MeshLab,
// Blender) before running it: scalar maps as vertex properties of their names, vector maps as face
// properties NAME_x, NAME_y, NAME_z in input coordinates. The parameters and controls that use the
// maps are evaluated too, so a map value out of a parameter's range is refused here as `run` would.
#include "common/errors.hpp"
#include "common/map_evaluation.hpp"
#include "common/scene.hpp"
#include "common/scene_maps.hpp"
#include "common/scene_surface.hpp"
#include "tools/commands.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

namespace physarum::cli {
namespace {

struct MapOptions {
  std::string scene;
  std::string out = "maps.ply";
};

int run_map(const MapOptions& o) {
  const Scene scene = load_scene(o.scene);
  if (scene.maps.empty()) throw InputError(o.scene + ": key 'maps': the scene defines no maps");
  const SceneSurface surface = prepare_scene_surface(scene, [](const std::string& line) { std::cerr << line << "\n"; });
  for (const std::string& w : surface.warnings) std::cerr << "physarum: warning: " << w << "\n";
  const EvaluatedMaps maps = evaluate_maps(scene.maps, surface, o.scene);
  // The same checks as `run`: parameter values in range, spawn weights usable.
  vertex_parameters(scene, surface, maps);
  simulation_controls(scene, surface, maps);
  const InputMaps on_input = maps_on_input(scene.maps, surface, maps, o.scene);
  write_maps_ply(o.out, surface.input, on_input);

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
  std::printf("physarum map: wrote %s\n", o.out.c_str());
  return 0;
}

}  // namespace

Command add_map_command(CLI::App& parent) {
  auto options = std::make_shared<MapOptions>();
  CLI::App* app = parent.add_subcommand(
      "map",
      "Evaluate a scene's named maps (key 'maps') on its surface and write them to a PLY of the input mesh: scalar "
      "maps per vertex (a property of the map's name), vector maps per face (NAME_x, NAME_y, NAME_z, input "
      "coordinates). Example: physarum map scene.json --out maps.ply");
  app->footer("Exit codes: 0 success, 1 bad input (nothing is written), 2 usage error.");
  app->add_option("scene", options->scene, "Scene file (JSON) with a 'maps' key")->required();
  app->add_option("--out", options->out, "The PLY file to write (its folder must exist)")->capture_default_str();
  return {app, [options] { return run_map(*options); }};
}

}  // namespace physarum::cli
