#include "tools/run_reaction_diffusion.hpp"

#include "common/atomic_write.hpp"
#include "common/cached_map_evaluation.hpp"
#include "common/errors.hpp"
#include "common/field_transfer.hpp"
#include "common/full_resolution_mesh.hpp"
#include "common/map_cache.hpp"
#include "common/map_evaluation.hpp"
#include "common/scene_maps.hpp"
#include "common/ply_writer.hpp"
#include "common/preview_image.hpp"
#include "common/reaction_diffusion_build.hpp"
#include "common/scene_surface.hpp"
#include "common/texture_bake.hpp"
#include "common/time_lapse.hpp"
#include "tools/backend_factory.hpp"
#include "tools/run_checkpoints.hpp"
#include "tools/surface_exports.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace physarum::cli {
namespace {

// About this many rows go into stats.csv, evenly spaced in steps (plus the initial row).
constexpr long long kStatsRows = 100;

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

}  // namespace

std::string morphogen_stats_header(const std::vector<std::string>& morphogens) {
  std::string header = "time";
  for (const std::string& m : morphogens) header += "," + m + "_mean," + m + "_variance";
  return header;
}

std::string morphogen_stats_row(double time, const std::vector<IntrinsicVertexData<double>>& layers,
                                const IntrinsicVertexData<double>& mass) {
  double area = 0.0;
  for (const double m : mass) area += m;
  std::string row = number(time);
  for (const IntrinsicVertexData<double>& u : layers) {
    double mean = 0.0;
    for (size_t i = 0; i < u.size(); ++i) mean += mass[i] * u[i];
    mean /= area;
    double variance = 0.0;
    for (size_t i = 0; i < u.size(); ++i) variance += mass[i] * (u[i] - mean) * (u[i] - mean);
    // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on the chained form.
    row += ',';
    row += number(mean);
    row += ',';
    row += number(variance / area);
  }
  return row;
}

int run_reaction_diffusion(const Scene& scene, const RunOptions& o, long long steps, const std::optional<ResumePoint>& resume) {
  const ReactionDiffusionSpec& spec = *scene.reaction_diffusion;
  TimeLapse time_lapse(o.frames, steps);

  // ---- everything that can reject the input, before any output exists ----
  const SceneSurface surface = prepare_scene_surface(scene, [](const std::string& line) { std::cerr << line << "\n"; });
  for (const std::string& w : surface.warnings) std::cerr << "physarum: warning: " << w << "\n";
  const SurfaceDomain& domain = surface.domain;
  // Through the map cache, as the agent model's maps: a geodesic distance or a direction field is
  // the slow part of a flower scene's start, and a sweep runs the same maps many times.
  MapEvaluationReport maps_report;
  const EvaluatedMaps maps = cached_evaluate_maps(map_sources_of(scene), surface, MapCache::from_environment(), &maps_report);
  if (!scene.maps.empty()) {
    for (const std::string& note : maps_report.notes) std::cerr << "physarum run: " << note << "\n";
    std::cerr << "physarum run: " << maps_report.summary() << "\n";
  }
  ReactionDiffusionSystem system = build_reaction_diffusion_system(scene, surface, maps);
  const int substeps = system.substeps;
  const std::vector<std::string> morphogens = system.morphogens;
  const int preview_layer = spec.morphogen_index(spec.preview_morphogen);
  const InputMesh& input = surface.input;
  const FullResolutionMesh full = build_full_resolution_mesh(input, domain);
  const std::optional<TexelLocations> texels = texels_for_run(input, domain, o.texture, "physarum run");
  const ChosenBackend chosen = choose_backend(o.backend, o.device);
  if (o.backend == "auto") std::cerr << "physarum run: " << to_string(chosen.backend) << " backend (auto: " << chosen.why << ")\n";
  if (system.integrator == ReactionIntegrator::Explicit && substeps > 1)
    std::cerr << "physarum run: " << substeps << " explicit sub-steps per step (the diffusion stability limit)\n";
  const std::unique_ptr<SimulationBackend> backend =
      make_reaction_diffusion_backend(chosen.backend, chosen.compute ? &*chosen.compute : nullptr, domain, std::move(system));
  SimulationBackend& simulation = *backend;
  // Written now, not with the results: a user checking the maps of a long run sees them at once.
  if (!o.maps_out.empty()) write_maps_ply(o.maps_out, input, maps_on_input(scene.maps, surface, maps, o.scene));

  auto layers = [&] {
    std::vector<IntrinsicVertexData<double>> all;
    for (int m = 0; m < simulation.dynamic_layer_count(); ++m) all.push_back(simulation.field_values(m));
    return all;
  };
  // Colours over 0 .. the preview morphogen's largest value (levels in multiples of half of it), so
  // the picture uses the whole colour map whatever the model's units.
  auto coloring_of = [&](const IntrinsicVertexData<double>& values) {
    const double top = values.empty() ? 1.0 : *std::max_element(values.begin(), values.end());
    return scene.colormap.mapping(top > 0.0 ? top / 2.0 : 1.0);
  };
  auto picture = [&] {
    const IntrinsicVertexData<double> values = simulation.field_values(preview_layer);
    PreviewOptions preview;
    preview.coloring = coloring_of(values);
    return render_preview(full.mesh, full.vertex_values(values), preview);
  };

  // ---- checkpoints, and where the run starts ----
  RunCheckpoints checkpoints(simulation, o, scene.mesh, scene.time_step, steps, resume);
  std::string stats;
  if (const std::string* resumed = checkpoints.resumed_stats()) {
    stats = *resumed;
  } else {
    stats = morphogen_stats_header(morphogens) + "\n";
    stats += morphogen_stats_row(simulation.time(), layers(), domain.vertex_mass) + "\n";
  }

  // ---- simulate ----
  const long long stats_every = std::max<long long>(1, steps / kStatsRows);
  checkpoints.start();
  double side_seconds = 0.0;  // statistics rows and frames: not simulation
  for (long long s = checkpoints.first_step(); s <= steps; ++s) {
    simulation.step();
    if (s % stats_every == 0 || s == steps || time_lapse.due(s)) {
      simulation.finish();  // the steps enqueued so far count as simulation, not as the reading below
      const auto ts = std::chrono::steady_clock::now();
      if (s % stats_every == 0 || s == steps)
        stats += morphogen_stats_row(simulation.time(), layers(), domain.vertex_mass) + "\n";
      if (time_lapse.due(s)) time_lapse.add(picture());
      side_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - ts).count();
    }
    checkpoints.after_step(s, simulation, stats, side_seconds);
  }
  simulation.finish();
  // A resumed run adds the seconds before its checkpoint.
  const double seconds = checkpoints.simulation_seconds(side_seconds);
  for (int m = 0; m < simulation.dynamic_layer_count(); ++m)
    for (const double x : simulation.field_values(m))
      if (!std::isfinite(x))
        throw InputError(scene.source + ": morphogen '" + morphogens[static_cast<size_t>(m)] +
                         "' is no longer finite: the run diverged (a smaller time_step, or \"integrator\": \"imex\")");

  // ---- outputs ----
  create_output_folder(o.out);
  const std::filesystem::path out(o.out);
  const std::vector<IntrinsicVertexData<double>> final_layers = layers();
  const IntrinsicVertexData<double>& shown = final_layers[static_cast<size_t>(preview_layer)];
  const double top = shown.empty() ? 0.0 : *std::max_element(shown.begin(), shown.end());
  const ColorMapping coloring = coloring_of(shown);
  std::vector<InputVertexData<double>> on_input, on_full;
  for (const auto& values : final_layers) {
    on_input.push_back(intrinsic_to_input(surface.input_to_intrinsic, values));
    on_full.push_back(full.vertex_values(values));
  }
  // The preview morphogen first: PLY vertex colours are the first field's.
  std::vector<size_t> order{static_cast<size_t>(preview_layer)};
  for (size_t m = 0; m < final_layers.size(); ++m)
    if (m != static_cast<size_t>(preview_layer)) order.push_back(m);
  std::vector<PlyField> input_fields, full_fields;
  for (const size_t m : order) {
    input_fields.push_back(PlyField{morphogens[m], on_input[m]});
    full_fields.push_back(PlyField{morphogens[m], on_full[m]});
  }
  write_fields_ply((out / "pheromone.ply").string(), input, input_fields, coloring, "morphogens per input vertex");
  write_fields_ply((out / "fields_full.ply").string(), full.mesh, full_fields, coloring,
                   "morphogens per intrinsic vertex (full resolution)");
  PreviewOptions preview;
  preview.coloring = coloring;
  write_preview_png((out / "preview.png").string(), full.mesh, on_full[static_cast<size_t>(preview_layer)], preview);
  const SurfaceExportsWritten exports = write_surface_exports(out, input, domain, texels, shown,
                                                              on_input[static_cast<size_t>(preview_layer)], coloring, o.texture);
  std::string written = "pheromone.ply, fields_full.ply, preview.png";
  for (const std::string& name : exports.files) written += ", " + name;
  write_text_file_atomically((out / "stats.csv").string(), stats);
  time_lapse.write(o.out);

  nlohmann::ordered_json j;
  j["backend"] = simulation.backend_name();
  j["backend_requested"] = o.backend;
  j["device"] = simulation.device_name();
  j["model"] = spec.model;
  j["morphogens"] = morphogens;
  j["preview_morphogen"] = spec.preview_morphogen;
  j["steps"] = steps;
  j["time_step"] = scene.time_step;
  j["sim_time"] = simulation.time();
  j["seconds"] = seconds;
  j["steps_per_second"] = seconds > 0 ? static_cast<double>(steps) / seconds : 0.0;
  j["integrator"] = spec.integrator == ReactionIntegrator::Explicit ? "forward" : "imex";
  j["substeps"] = substeps;
  j["seed"] = scene.seed;
  for (size_t m = 0; m < final_layers.size(); ++m) {
    const auto& u = final_layers[m];
    j["final"][morphogens[m]] = {{"min", *std::min_element(u.begin(), u.end())},
                                 {"max", *std::max_element(u.begin(), u.end())}};
  }
  j["intrinsic_vertices"] = domain.vertex_count;
  j["intrinsic_faces"] = domain.face_count;
  j["area"] = domain.total_area;
  j["scene_file"] = o.scene;
  j["surface"] = surface_spec_json(SurfaceSpec::of(scene));
  if (texels) j["texture"] = o.texture.to_json();
  // What `physarum render` recolours by: the colour map and the unit its levels count in (half the
  // preview morphogen's largest value, as coloring_of chose; an agent run's unit is U).
  j["colormap"] = color_map_settings_json(scene.colormap);
  j["color_unit"] = top > 0.0 ? top / 2.0 : 1.0;
  j["reaction_diffusion"] = reaction_diffusion_json(spec);
  if (!scene.maps.empty()) j["maps"] = scene.maps_given;
  checkpoints.record(j);
  write_text_file_atomically((out / "run.json").string(), j.dump(2) + "\n");
  checkpoints.remove_file();

  std::cout << "physarum run: " << spec.model << ", " << steps << " steps (" << simulation.time() << " s simulated, "
            << substeps << " sub-step" << (substeps > 1 ? "s" : "") << " each) in " << seconds << " s; wrote "
            << out.string() << "/{" << written << ", stats.csv, run.json"
            << (time_lapse.enabled() ? ", frames/, frames.gif" : "") << "}"
            << (o.maps_out.empty() ? std::string() : " and " + o.maps_out) << "\n";
  return 0;
}

}  // namespace physarum::cli
