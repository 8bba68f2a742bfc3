// `physarum run SCENE.json [--set KEY=VALUE ...] [--backend auto|reference|opencl] [--steps N | --sim-time T]
//  [--seed S] [--out DIR] [--frames K] [--texture-size N] [--texture-margin PX] [--texture-format png|png16|exr]
//  [--checkpoint-every T]`, or `physarum run --resume DIR`:
// grows a pattern on a surface and writes (the README's "The command line")
//   DIR/pheromone.ply    the input mesh with the field at its vertices,
//   DIR/fields_full.ply  the result at full resolution: every intrinsic vertex at its place on the
//                        input surface, intrinsic connectivity, the exact values (full_resolution_mesh.hpp),
//   DIR/preview.png      drawn from the full-resolution mesh,
//   DIR/texture.png      the field baked onto the input's UVs with padded seams (texture_bake.hpp),
//                        8-bit, or 16-bit with --texture-format png16; with exr also DIR/texture.exr
//                        (raw float values); skipped, with a note, when the mesh has no UVs,
//   DIR/result.glb       glTF 2.0 binary of the input mesh (colours, values, UVs, the texture),
//   DIR/stats.csv and DIR/run.json;
// with --frames K also a time-lapse, DIR/frames/frame_NNNN.png and DIR/frames.gif.
//
// With --checkpoint-every T, DIR/checkpoint.bin holds the whole state every T simulated seconds
// (common/checkpoint.hpp), replaced atomically; `physarum run --resume DIR` continues from it bit for
// bit (same build, backend and device; the scene unchanged) and writes what the uninterrupted run
// would have written. The checkpoint is removed once the run's outputs are complete.
//
// Everything that can fail on bad input (scene, mesh, triangulation, the UV map) happens before DIR
// is touched, so a bad scene exits 1 with its message and writes nothing; every file is written under
// a temporary name and renamed, so a reader never sees a half-written one.
#include "common/atomic_write.hpp"
#include "common/checkpoint.hpp"
#include "common/color_map_json.hpp"
#include "common/errors.hpp"
#include "common/field_statistics.hpp"
#include "common/field_transfer.hpp"
#include "common/full_resolution_mesh.hpp"
#include "common/input_mesh.hpp"
#include "common/map_evaluation.hpp"
#include "common/ply_writer.hpp"
#include "common/preview_image.hpp"
#include "common/scene.hpp"
#include "common/scene_json.hpp"
#include "common/scene_maps.hpp"
#include "common/simulation_state.hpp"
#include "common/scene_surface.hpp"
#include "common/species_statistics.hpp"
#include "common/surface_domain.hpp"
#include "common/texture_bake.hpp"
#include "common/time_lapse.hpp"
#include "common/workload.hpp"
#include "opencl/compute_context.hpp"
#include "tools/backend_factory.hpp"
#include "tools/commands.hpp"
#include "tools/feasible_surface.hpp"
#include "tools/run_options.hpp"
#include "tools/resume_point.hpp"
#include "tools/run_checkpoints.hpp"
#include "tools/run_reaction_diffusion.hpp"
#include "tools/surface_exports.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <unistd.h>

namespace physarum::cli {
namespace {


// About this many rows go into stats.csv, evenly spaced in steps (plus the initial row).
constexpr long long kStatsRows = 100;

long long run_length_in_steps(const RunOptions& o, const Scene& scene) {
  auto steps_for = [&](double seconds) {
    // Nearest whole step: T / dt often lands a rounding error away from an integer.
    return std::max<long long>(1, std::llround(seconds / scene.time_step));
  };
  if (o.steps) return *o.steps;
  if (o.sim_time) return steps_for(*o.sim_time);
  if (scene.steps) return *scene.steps;
  if (scene.sim_time) return steps_for(*scene.sim_time);
  throw UsageError("no run length: give --steps N or --sim-time T (or 'steps' / 'sim_time' in " + o.scene + ")");
}

// A one-line progress bar with ETA on stderr, drawn only when stderr is a terminal.
class ProgressBar {
 public:
  explicit ProgressBar(long long total) : total_(total), enabled_(::isatty(STDERR_FILENO) == 1) {}
  void update(long long done) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (done < total_ && now - last_draw_ < std::chrono::milliseconds(200)) return;
    last_draw_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double fraction = total_ > 0 ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
    const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    constexpr int kWidth = 40;
    const int filled = static_cast<int>(fraction * kWidth);
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  step %lld/%lld  ETA %.0f s ", std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, ' ').c_str(), 100.0 * fraction, done, total_, eta);
    if (done >= total_) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  long long total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_draw_{};
};


int run_simulation(const RunOptions& o, const std::optional<ResumePoint>& resume) {
  if (!o.device.empty() && o.backend == "reference") throw UsageError("--device applies to the OpenCL backend only");
  if (o.steps && *o.steps < 1) throw UsageError("--steps " + std::to_string(*o.steps) + " must be >= 1");
  if (o.sim_time && !(*o.sim_time > 0.0)) throw UsageError("--sim-time must be > 0");
  if (o.checkpoint_every && !(*o.checkpoint_every > 0.0)) throw UsageError("--checkpoint-every must be > 0");
  if (o.checkpoint_every && o.frames > 0)
    throw UsageError("--frames does not go with --checkpoint-every: the frames drawn before a stop are not in the "
                     "checkpoint, so a resumed run's time-lapse would miss them");
  o.texture.check();

  // ---- everything that can reject the input, before any output exists ----
  Scene given_scene = load_scene(o.scene, o.overrides());
  if (o.seed) given_scene.seed = *o.seed;
  if (!o.maps_out.empty() && given_scene.maps.empty())
    throw UsageError("--maps-out: " + o.scene + " defines no maps (key 'maps')");
  const long long steps = run_length_in_steps(o, given_scene);
  if (is_reaction_diffusion(given_scene)) return run_reaction_diffusion(given_scene, o, steps, resume);
  TimeLapse time_lapse(o.frames, steps);

  // The maps, evaluated once (through the map cache) with the surface: the per-vertex parameters and
  // controls the backend is built from, and what --maps-out writes. `scene` summarises each mapped
  // parameter by its mean (U, run.json).
  const FeasibleSurface feasible = prepare_feasible_surface(given_scene, steps, MapCache::from_environment());
  const SceneSurface& surface = feasible.surface;
  const SurfaceDomain& domain = surface.domain;
  const EvaluatedMaps& maps = feasible.maps;
  if (!given_scene.maps.empty()) {
    for (const std::string& note : feasible.maps_report.notes) std::cerr << "physarum run: " << note << "\n";
    std::cerr << "physarum run: " << feasible.maps_report.summary() << "\n";
  }
  const SceneArrays arrays = scene_arrays(given_scene, surface, maps);
  const Scene scene = with_mean_parameters(given_scene, arrays.parameters, domain);
  const InputMesh& input = surface.input;
  const FullResolutionMesh full = build_full_resolution_mesh(input, domain);
  const std::optional<TexelLocations> texels = texels_for_run(input, domain, o.texture, "physarum run");
  const ChosenBackend chosen = choose_backend(o.backend, o.device);
  const BackendChoice choice = chosen.backend;
  const std::optional<opencl::ComputeContext>& compute = chosen.compute;
  if (o.backend == "auto") std::cerr << "physarum run: " << to_string(choice) << " backend (auto: " << chosen.why << ")\n";
  const std::unique_ptr<SimulationBackend> backend =
      make_backend(choice, compute ? &*compute : nullptr, domain, scene, arrays);  // refuses what does not fit in memory
  SimulationBackend& simulation = *backend;
  // Written now, not with the results: a user checking the maps of a long run sees them at once.
  if (!o.maps_out.empty())
    write_maps_ply(o.maps_out, input, maps_on_input(given_scene.maps, surface, maps, o.scene));
  const double U = uniform_steady_state(scene, domain.total_area);
  // Colours span the scene's levels in multiples of U (default 0 .. 2U, the range the coverage
  // columns talk about), so pictures of different runs of one scene (and the frames of one run) are
  // comparable; the value itself is in the PLY property.
  const FieldColoring coloring = scene.colormap.mapping(U);
  PreviewOptions preview;
  preview.coloring = coloring;
  // Competing species (common/species_statistics.hpp): each species' U and layer statistics beside
  // the existing columns (which stay layer 0's, with the scene's U), and pictures in one colour per
  // species, each layer coloured over its own species' levels.
  const int species_layers = simulation.dynamic_layer_count();
  const std::vector<double> species_U =
      species_layers > 1 ? species_steady_states(scene, arrays.species, domain) : std::vector<double>{};
  std::vector<FieldColoring> species_colorings;
  for (const double Us : species_U) species_colorings.push_back(scene.colormap.mapping(Us));
  auto species_statistics = [&] {
    std::vector<FieldStatistics> per_species;
    for (int layer = 0; layer < static_cast<int>(species_U.size()); ++layer)
      per_species.push_back(simulation.field_statistics(species_U[static_cast<size_t>(layer)], layer));
    return per_species;
  };
  auto stats_row = [&] {
    return stats_csv_row(simulation.time(), simulation.field_statistics(U)) + species_stats_csv_values(species_statistics());
  };
  // Pictures (preview and time-lapse frames) are drawn from the full-resolution mesh: every detail
  // the simulation resolved, not only its values at the input vertices.
  auto picture = [&] {
    if (species_layers <= 1) return render_preview(full.mesh, full.vertex_values(simulation.field_values()), preview);
    std::vector<InputVertexData<double>> layers;
    for (int layer = 0; layer < species_layers; ++layer) layers.push_back(full.vertex_values(simulation.field_values(layer)));
    return render_species_preview(full.mesh, layers, species_colorings, preview);
  };

  // ---- checkpoints, and where the run starts ----
  RunCheckpoints checkpoints(simulation, o, given_scene.mesh, scene.time_step, steps, resume);
  std::string stats;
  if (const std::string* resumed = checkpoints.resumed_stats()) {
    stats = *resumed;
  } else {
    stats = stats_csv_header() + species_stats_csv_columns(species_layers) + "\n";
    stats += stats_row() + "\n";
  }

  // ---- simulate ----
  const long long stats_every = std::max<long long>(1, steps / kStatsRows);
  ProgressBar progress(steps);
  checkpoints.start();
  double stats_seconds = 0.0;
  for (long long s = checkpoints.first_step(); s <= steps; ++s) {
    simulation.step();
    if (s % stats_every == 0 || s == steps) {
      simulation.finish();
      const auto ts = std::chrono::steady_clock::now();
      stats += stats_row() + "\n";
      stats_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - ts).count();
    }
    if (time_lapse.due(s)) {
      simulation.finish();
      const auto tf = std::chrono::steady_clock::now();
      time_lapse.add(picture());
      stats_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - tf).count();
    }
    checkpoints.after_step(s, simulation, stats, stats_seconds);
    progress.update(s);
  }
  simulation.finish();
  // Throughput counts the simulation alone, not the statistics rows, the time-lapse frames or the
  // checkpoints; a resumed run adds the seconds before its checkpoint.
  const double seconds = checkpoints.simulation_seconds(stats_seconds);
  const FieldStatistics final_stats = simulation.field_statistics(U);
  const std::vector<FieldStatistics> final_species_stats = species_statistics();

  // ---- outputs ----
  create_output_folder(o.out);
  const std::filesystem::path out(o.out);

  const IntrinsicVertexData<double> field = simulation.field_values();
  const InputVertexData<double> on_input = intrinsic_to_input(surface.input_to_intrinsic, field);
  const InputVertexData<double> on_full = full.vertex_values(field);
  std::string written = "pheromone.ply, fields_full.ply";
  // Competing species: one property per species' layer, pheromone_0, pheromone_1, ..., beside
  // "pheromone" (= layer 0, kept so readers of one-species outputs still find it).
  std::vector<InputVertexData<double>> species_on_input, species_on_full;
  for (int layer = 0; species_layers > 1 && layer < species_layers; ++layer) {
    const IntrinsicVertexData<double> values = simulation.field_values(layer);
    species_on_input.push_back(intrinsic_to_input(surface.input_to_intrinsic, values));
    species_on_full.push_back(full.vertex_values(values));
  }
  std::vector<PlyField> input_fields{PlyField{"pheromone", on_input}}, full_fields{PlyField{"pheromone", on_full}};
  for (size_t layer = 0; layer < species_on_input.size(); ++layer) {
    input_fields.push_back(PlyField{"pheromone_" + std::to_string(layer), species_on_input[layer]});
    full_fields.push_back(PlyField{"pheromone_" + std::to_string(layer), species_on_full[layer]});
  }
  write_fields_ply((out / "pheromone.ply").string(), input, input_fields, coloring, "pheromone per input vertex");
  write_fields_ply((out / "fields_full.ply").string(), full.mesh, full_fields, coloring,
                   "pheromone per intrinsic vertex (full resolution)");
  if (species_layers > 1)
    write_rgb_png((out / "preview.png").string(), render_species_preview(full.mesh, species_on_full, species_colorings, preview));
  else
    write_preview_png((out / "preview.png").string(), full.mesh, on_full, preview);
  const SurfaceExportsWritten exports =
      write_surface_exports(out, input, domain, texels, field, on_input, coloring, o.texture);
  for (const std::string& name : exports.files) written += ", " + name;
  write_text_file_atomically((out / "stats.csv").string(), stats);
  time_lapse.write(o.out);

  const SimulationCounters c = simulation.counters();
  nlohmann::ordered_json j;
  j["backend"] = simulation.backend_name();
  j["backend_requested"] = o.backend;
  j["device"] = simulation.device_name();
  j["steps"] = steps;
  j["sim_time"] = simulation.time();
  j["seconds"] = seconds;
  j["agent_steps_per_second"] = seconds > 0 ? static_cast<double>(c.agent_steps) / seconds : 0.0;
  j["face_crossings_per_agent_step"] = c.crossings_per_agent_step();
  j["face_crossings_per_second"] =
      seconds > 0 ? static_cast<double>(c.face_crossings + c.sensor_face_crossings) / seconds : 0.0;
  j["move_crossings_per_agent_step"] =
      c.agent_steps > 0 ? static_cast<double>(c.face_crossings) / static_cast<double>(c.agent_steps) : 0.0;
  j["U"] = U;
  j["mean"] = final_stats.mean;
  j["coverage_0.5U"] = final_stats.coverage[0];
  j["coverage_1U"] = final_stats.coverage[1];
  j["coverage_2U"] = final_stats.coverage[2];
  j["intrinsic_vertices"] = domain.vertex_count;
  j["intrinsic_faces"] = domain.face_count;
  j["area"] = domain.total_area;
  j["respawns"] = c.respawns;
  // Competing species: per species its agents, steady state U_i, and its layer's mean and coverage
  // (the keys above are layer 0's); the preview's colour of each as #rrggbb.
  for (size_t s = 0; s < final_species_stats.size(); ++s) {
    const FieldStatistics& f = final_species_stats[s];
    const std::array<double, 3> colour = species_colour(static_cast<int>(s));
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", static_cast<unsigned>(std::lround(colour[0] * 255)),
                  static_cast<unsigned>(std::lround(colour[1] * 255)), static_cast<unsigned>(std::lround(colour[2] * 255)));
    j["species_layers"].push_back({{"species", s},
                                   {"agents", arrays.species.species[s].agents},
                                   {"U", f.U},
                                   {"mean", f.mean},
                                   {"coverage_0.5U", f.coverage[0]},
                                   {"coverage_1U", f.coverage[1]},
                                   {"coverage_2U", f.coverage[2]},
                                   {"preview_colour", hex}});
  }
  // For readers that check result.glb: its vertices are the input's plus copies along UV seams.
  j["result_glb_vertices"] = exports.glb.vertices;
  j["result_glb_seam_splits"] = exports.glb.seam_splits;
  j["scene_file"] = o.scene;
  // What `physarum render` needs to rebuild the surface and bake the texture again.
  j["surface"] = surface_spec_json(SurfaceSpec::of(scene));
  if (texels) j["texture"] = o.texture.to_json();
  j["parameters"] = scene_parameters_json(scene);
  // The colours as used (stops, levels in multiples of U): `physarum render` re-colours with it.
  j["colormap"] = color_map_settings_json(scene.colormap);
  checkpoints.record(j);
  write_text_file_atomically((out / "run.json").string(), j.dump(2) + "\n");
  checkpoints.remove_file();

  std::cout << "physarum run: " << steps << " steps (" << simulation.time() << " s simulated) in " << seconds
            << " s, " << j["agent_steps_per_second"].get<double>() << " agent-steps/s; mean " << final_stats.mean
            << ", U " << U << "; wrote " << out.string() << "/{" << written << ", preview.png, stats.csv, run.json"
            << (time_lapse.enabled() ? ", frames/, frames.gif" : "") << "}"
            << (o.maps_out.empty() ? std::string() : " and " + o.maps_out) << "\n";
  return 0;
}

int run_run(const RunOptions& given) {
  if (given.resume.empty()) {
    if (given.scene.empty()) throw UsageError("give a scene file (or --resume DIR)");
    return run_simulation(given, std::nullopt);
  }
  // A resume is the stopped run itself: its options all come from the checkpoint. A scene given
  // beside --resume must be the same one (its identity hash is checked against the checkpoint's).
  if (!given.sets.empty() || given.steps || given.sim_time || given.seed || given.frames > 0 || given.checkpoint_every ||
      !given.maps_out.empty())
    throw UsageError("--resume DIR continues the run with the options it was started with; give no other run "
                     "option beside it (the scene, to check it is the same, is allowed)");
  ResumePoint resume;
  resume.path = (std::filesystem::path(given.resume) / "checkpoint.bin").string();
  if (!std::filesystem::exists(resume.path))
    throw InputError(resume.path + ": no checkpoint to resume from (was the run started with --checkpoint-every, "
                                   "and has it finished already? A finished run removes its checkpoint)");
  resume.checkpoint = read_checkpoint(resume.path);
  RunOptions o = run_options_from_json(resume.checkpoint.header.run.at("options"), resume.path);
  if (!given.scene.empty()) o.scene = given.scene;
  o.out = given.resume;
  return run_simulation(o, resume);
}

}  // namespace

Command add_run_command(CLI::App& parent) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* app = parent.add_subcommand(
      "run",
      "Grow a slime-mold pattern on a surface and write DIR/pheromone.ply (the input mesh with the per-vertex "
      "pheromone), DIR/fields_full.ply (the result at full resolution: every intrinsic vertex on the input surface, "
      "exact values), DIR/texture.png (the pheromone baked onto the mesh's UVs; not for meshes without UVs), "
      "DIR/result.glb (glTF 2.0 binary of the input mesh for any 3D viewer: linear vertex colours, the values as _PHEROMONE, UVs and the baked texture where the mesh has UVs), "
      "DIR/stats.csv (time,mean,U,coverage_0.5U,coverage_1U,coverage_2U), DIR/preview.png (from the full-resolution "
      "mesh) and DIR/run.json (parameters, device, timings). Competing species ('species'): pheromone_0, pheromone_1, "
      "... in the PLYs, stats.csv columns mean_i,U_i, run.json 'species_layers', one colour per species in the "
      "pictures. Example: physarum run tools/scenes/default.json --out out");
  app->footer(
      "Run length: --steps, else --sim-time, else the scene's 'steps', else its 'sim_time' (one of them is "
      "required). The scene is one JSON object with the model parameters in SI units, angles in degrees; "
      "'mesh' is a file path relative to the scene file or shape:NAME (tools/scenes/ has examples; README.md "
      "lists every key). Exit codes: 0 success, 1 bad input (nothing is written), 2 usage error.");
  app->add_option("scene", options->scene,
                  "Scene file (JSON), e.g. tools/scenes/default.json, the built-in default scene (a sphere); "
                  "required unless --resume");
  app->add_option("--set", options->sets,
                  "Override a scene key, KEY=VALUE (repeatable). VALUE is JSON where it parses (90, true, [0.5,1.5], "
                  "{\"map\":\"ramp\"}), else a string; KEY may be nested with dots: maps.ramp.range=[0.5,1.5], "
                  "bias.strength=40, read_stimuli.0.weight=-0.5 (a number after a dot indexes a list)");
  app->add_option("--checkpoint-every", options->checkpoint_every,
                  "Write DIR/checkpoint.bin (the whole state) every T simulated seconds, replacing the previous one "
                  "atomically; removed when the run finishes. A stopped run continues with --resume DIR");
  app->add_option("--resume", options->resume,
                  "Continue the stopped run in DIR from DIR/checkpoint.bin, bit for bit as if never stopped (same "
                  "build, backend and device; a checkpoint of another scene, build, backend or device, or a corrupted "
                  "one, is refused). Takes every option from the checkpoint");
  app->add_option("--backend", options->backend,
                  "Simulation backend: auto (OpenCL where a device exists, else the reference), reference or opencl")
      ->check(CLI::IsMember({"auto", "reference", "opencl"}))
      ->capture_default_str();
  app->add_option("--device", options->device,
                  "OpenCL device: an index from `physarum devices` or a name substring (default: $PHYSARUM_DEVICE, "
                  "then the first GPU, then the first device)");
  auto* steps = app->add_option("--steps", options->steps, "Number of time steps (overrides the scene's run length)");
  auto* sim_time = app->add_option("--sim-time", options->sim_time, "Simulated seconds, rounded to whole time steps (overrides the scene's run length)");
  steps->excludes(sim_time);
  app->add_option("--seed", options->seed, "Random seed (overrides the scene)");
  app->add_option("--out", options->out, "Output folder (created if needed)")->capture_default_str();
  app->add_option("--frames", options->frames,
                  "Time-lapse: K pictures evenly spaced in steps (the last at the final step), written as "
                  "DIR/frames/frame_0001.png ... and the animated DIR/frames.gif");
  app->add_option("--maps-out", options->maps_out,
                  "Also write the scene's named maps (key 'maps') to this PLY on the input mesh: scalar maps per "
                  "vertex, vector maps per face as NAME_x, NAME_y, NAME_z (what `physarum map` writes)");
  app->add_option("--texture-size", options->texture.size,
                  "Side of the square texture baked onto the mesh's UVs, in texels (1.." +
                      std::to_string(TexelLocations::kMaxSize) + ")")
      ->capture_default_str();
  app->add_option("--texture-margin", options->texture.margin,
                  "Seam padding of the texture: texels outside the UV charts within this many texels of one take "
                  "values continued from it")
      ->capture_default_str();
  app->add_option("--texture-format", options->texture.format,
                  "png: texture.png, 8-bit sRGB colours; png16: texture.png with 16 bits per channel; exr: texture.png "
                  "and texture.exr, the raw float values in a channel named pheromone")
      ->check(CLI::IsMember({"png", "png16", "exr"}))
      ->capture_default_str();
  return Command{app, [options] { return run_run(*options); }};
}

}  // namespace physarum::cli
