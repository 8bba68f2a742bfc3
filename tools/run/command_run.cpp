// `physarum run SCENE.json [--set KEY=VALUE ...] [--backend auto|reference|opencl] [--steps N | --sim-time T]
//  [--seed S] [--out DIR] [--frames K] [--texture-size N] [--texture-margin PX] [--texture-format png|png16|exr]
//  [--checkpoint-every T]`, or `physarum run --resume DIR`:
// grows a pattern on a surface and writes (docs/commands.md)
//   DIR/pheromone.ply    the input mesh with the field at its vertices,
//   DIR/fields_full.ply  the result at full resolution: every intrinsic vertex at its place on the
//                        input surface, intrinsic connectivity, the exact values (full_resolution_mesh.hpp),
//   DIR/preview.png      drawn from the full-resolution mesh,
//   DIR/texture.png      the field baked onto the input's UVs with padded seams (texture_bake.hpp),
//                        8-bit, or 16-bit with --texture-format png16; with exr also DIR/texture.exr
//                        (raw float values); skipped, with a note, when the mesh has no UVs,
//   DIR/result.glb       glTF 2.0 binary: the input mesh with UVs and the baked texture, or without
//                        UVs the full-resolution mesh with its colours (surface_exports.hpp),
//   DIR/stats.csv and DIR/run.json;
// with --frames K also a time-lapse, DIR/frames/frame_NNNN.png and DIR/frames.gif.
//
// With --checkpoint-every T, DIR/checkpoint.bin holds the whole state every T simulated seconds
// (common/run/checkpoint.hpp), replaced atomically; `physarum run --resume DIR` continues from it bit for
// bit (same build, backend and device; the scene unchanged) and writes what the uninterrupted run
// would have written. The checkpoint is removed once the run's outputs are complete.
//
// Everything that can fail on bad input (scene, mesh, triangulation, the UV map) happens before DIR
// is touched, so a bad scene exits 1 with its message and writes nothing; every file is written under
// a temporary name and renamed, so a reader never sees a half-written one.
#include "common/setup/agent_inputs.hpp"
#include "common/color/color_map_json.hpp"
#include "common/base/errors.hpp"
#include "common/base/overloaded.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/output/preview_image.hpp"
#include "common/scene/scene.hpp"
#include "common/scene/scene_json.hpp"
#include "common/setup/species_statistics.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/output/texture_bake.hpp"
#include "tools/commands.hpp"
#include "tools/run/run_options.hpp"
#include "tools/run/resume_point.hpp"
#include "tools/run/run_checkpoints.hpp"
#include "api/session.hpp"
#include "tools/run/run_loop.hpp"
#include "tools/run/prepared_run.hpp"
#include "tools/run/run_reaction_diffusion.hpp"
#include "tools/run/surface_exports.hpp"

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
#include <sstream>
#include <string>
#include <unistd.h>

namespace physarum::cli {
namespace {


// The agent model's run.json keys: throughput, Eq. 5's U and the final statistics, per species its
// own, and the parameters as run.
void agent_run_json(nlohmann::ordered_json& j, const SimulationBackend& simulation, const Scene& scene,
                    const SceneArrays& arrays, double U, const std::vector<double>& species_U, double seconds) {
  const SimulationCounters c = simulation.counters();
  j["agent_steps_per_second"] = seconds > 0 ? static_cast<double>(c.agent_steps) / seconds : 0.0;
  j["face_crossings_per_agent_step"] = c.crossings_per_agent_step();
  j["face_crossings_per_second"] =
      seconds > 0 ? static_cast<double>(c.face_crossings + c.sensor_face_crossings) / seconds : 0.0;
  j["move_crossings_per_agent_step"] =
      c.agent_steps > 0 ? static_cast<double>(c.face_crossings) / static_cast<double>(c.agent_steps) : 0.0;
  const FieldStatistics final_stats = simulation.field_statistics(U);
  j["U"] = U;
  j["mean"] = final_stats.mean;
  j["coverage_0.5U"] = final_stats.coverage[0];
  j["coverage_1U"] = final_stats.coverage[1];
  j["coverage_2U"] = final_stats.coverage[2];
  j["respawns"] = c.respawns;
  // Competing species: per species its agents, steady state U_i, and its layer's mean and coverage
  // (the keys above are layer 0's); the preview's colour of each as #rrggbb.
  for (size_t s = 0; s < species_U.size(); ++s) {
    const FieldStatistics f = simulation.field_statistics(species_U[s], static_cast<int>(s));
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
  j["parameters"] = scene_parameters_json(scene);
}

// The flags' own checks, before the scene is read.
void check_run_options(const RunOptions& o) {
  if (!o.device.empty() && o.backend == "reference") throw UsageError("--device applies to the OpenCL backend only");
  if (o.steps && *o.steps < 1) throw UsageError("--steps " + std::to_string(*o.steps) + " must be >= 1");
  if (o.sim_time && !(*o.sim_time > 0.0)) throw UsageError("--sim-time must be > 0");
  if (o.checkpoint_every && !(*o.checkpoint_every > 0.0)) throw UsageError("--checkpoint-every must be > 0");
  if (o.checkpoint_every && o.frames > 0)
    throw UsageError("--frames does not go with --checkpoint-every: the frames drawn before a stop are not in the "
                     "checkpoint, so a resumed run's time-lapse would miss them");
  o.texture.check();
}

// The agent model's run: its surface, maps and backend, and what it writes.
class AgentRun final : public PreparedRun {
 public:
  AgentRun(const Scene& given_scene, const RunOptions& o, long long steps, const std::optional<ResumePoint>& resume)
      : PreparedRun(given_scene, o, steps, resume),
        simulation_(session_.backend()),
        full_(build_full_resolution_mesh(session_.surface().input, session_.surface().domain)) {
    // The surface, the maps (evaluated once, through the map cache) and the backend are the
    // session's. Its scene summarises each mapped parameter by its mean (U, run.json).
    const Scene& scene = session_.scene();
    const SurfaceDomain& domain = session_.surface().domain;
    std::optional<TexelLocations> texels = texels_for_run(session_.surface().input, domain, o.texture, "physarum run");
    U_ = uniform_steady_state(scene, domain.total_area);
    // Colours span the scene's levels in multiples of U (default 0 .. 2U, the range the coverage
    // columns talk about), so pictures of different runs of one scene (and the frames of one run) are
    // comparable; the value itself is in the PLY property.
    coloring_ = scene.color_map.mapping(U_);
    preview_.coloring = coloring_;
    // Competing species (common/setup/species_statistics.hpp): each species' U and layer statistics beside
    // the existing columns (which stay layer 0's, with the scene's U), and pictures in one colour per
    // species, each layer coloured over its own species' levels.
    species_layers_ = simulation_.dynamic_layer_count();
    if (species_layers_ > 1) species_U_ = species_steady_states(scene, session_.agent_arrays()->species, domain);
    for (const double Us : species_U_) species_colorings_.push_back(scene.color_map.mapping(Us));
    describe_outputs(steps);
    start(session_.surface(), full_, std::move(texels));
  }

 private:
  std::vector<FieldStatistics> species_statistics() const {
    std::vector<FieldStatistics> per_species;
    for (int layer = 0; layer < static_cast<int>(species_U_.size()); ++layer)
      per_species.push_back(simulation_.field_statistics(species_U_[static_cast<size_t>(layer)], layer));
    return per_species;
  }
  // Pictures (preview and time-lapse frames) are drawn from the full-resolution mesh: every detail
  // the simulation resolved, not only its values at the input vertices.
  RgbImage picture() const {
    if (species_layers_ <= 1) return render_preview(full_.mesh, full_.vertex_values(simulation_.field_values()), preview_);
    std::vector<InputVertexData<double>> layers;
    for (int layer = 0; layer < species_layers_; ++layer) layers.push_back(full_.vertex_values(simulation_.field_values(layer)));
    return render_species_preview(full_.mesh, layers, species_colorings_, preview_);
  }

  // ---- what the agent model writes (the run itself is the one run loop's) ----
  void describe_outputs(long long steps) {
    model_.fields_file = "pheromone.ply";
    model_.fields_description = "pheromone";
    model_.stats_header = stats_csv_header() + species_stats_csv_columns(species_layers_);
    model_.stats_row = [this] {
      return stats_csv_row(simulation_.time(), simulation_.field_statistics(U_)) +
             species_stats_csv_values(species_statistics());
    };
    model_.frame = [this] { return picture(); };
    model_.result = [this] {
      ModelResult r;
      r.coloring = coloring_;
      // Competing species: one property per species' layer, pheromone_0, pheromone_1, ..., beside
      // "pheromone" (= layer 0, kept so readers of one-species outputs still find it).
      r.layers.emplace_back("pheromone", simulation_.field_values());
      for (int layer = 0; species_layers_ > 1 && layer < species_layers_; ++layer)
        r.layers.emplace_back("pheromone_" + std::to_string(layer), simulation_.field_values(layer));
      if (species_layers_ > 1) r.preview = picture();
      return r;
    };
    model_.run_json = [this](nlohmann::ordered_json& j, double seconds) {
      agent_run_json(j, simulation_, session_.scene(), *session_.agent_arrays(), U_, species_U_, seconds);
    };
    model_.summary = [this, steps](double seconds) {
      const SimulationCounters c = simulation_.counters();
      std::ostringstream line;
      line << steps << " steps (" << simulation_.time() << " s simulated) in " << seconds << " s, "
           << (seconds > 0 ? static_cast<double>(c.agent_steps) / seconds : 0.0) << " agent-steps/s; mean "
           << simulation_.field_statistics(U_).mean << ", U " << U_;
      return line.str();
    };
  }

  SimulationBackend& simulation_;
  const FullResolutionMesh full_;
  double U_ = 0.0;
  FieldColoring coloring_;
  PreviewOptions preview_;
  int species_layers_ = 1;
  std::vector<double> species_U_;
  std::vector<FieldColoring> species_colorings_;
};

}  // namespace

std::unique_ptr<PreparedRun> prepare_agent_run(const Scene& scene, const RunOptions& options, long long steps,
                                               const std::optional<ResumePoint>& resume) {
  return std::make_unique<AgentRun>(scene, options, steps, resume);
}

namespace {

// Reads the scene (with the options' overrides and seed) and dispatches once, on its model.
int run_simulation(const RunOptions& o, const std::optional<ResumePoint>& resume) {
  check_run_options(o);
  // ---- everything that can reject the input, before any output exists ----
  Scene scene = load_scene(o.scene, o.overrides());
  if (o.seed) scene.seed = *o.seed;
  if (!o.maps_out.empty() && scene.maps.empty()) throw UsageError("--maps-out: " + o.scene + " defines no maps (key 'maps')");
  const long long steps = run_length_in_steps(o, scene);
  std::unique_ptr<PreparedRun> run = prepare_run(scene, o, steps, resume);
  return run->finish_and_write();
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

int run_scene(const RunOptions& options) { return run_simulation(options, std::nullopt); }

Command add_run_command(CLI::App& parent) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* app = parent.add_subcommand(
      "run",
      "Grow a pattern (agents or reaction-diffusion) on a surface and write its outputs\n"
      "Grow a slime-mold pattern on a surface and write DIR/pheromone.ply (the input mesh with the per-vertex "
      "pheromone), DIR/fields_full.ply (the result at full resolution: every intrinsic vertex on the input surface, "
      "exact values), DIR/texture.png (the pheromone baked onto the mesh's UVs; not for meshes without UVs), "
      "DIR/result.glb (glTF 2.0 binary for any 3D viewer with the run's whole detail: the input mesh, its UVs and the baked texture where the mesh has UVs, else the full-resolution mesh with linear vertex colours; the values as _PHEROMONE), "
      "DIR/stats.csv (time,mean,U,coverage_0.5U,coverage_1U,coverage_2U), DIR/preview.png (from the full-resolution "
      "mesh) and DIR/run.json (parameters, device, timings). Competing species ('species'): pheromone_0, pheromone_1, "
      "... in the PLYs, stats.csv columns mean_i,U_i, run.json 'species_layers', one colour per species in the "
      "pictures. Reaction-diffusion scenes: DIR/morphogens.ply (every morphogen a property of its name) instead of "
      "pheromone.ply, stats.csv columns time,<m>_mean,<m>_variance,... Example: physarum run tools/scenes/default.json "
      "--out out");
  app->footer(
      "Run length: --steps, else --sim-time, else the scene's 'steps', else its 'sim_time' (one of them is "
      "required). The scene is one JSON object with the model parameters in SI units, angles in degrees; "
      "'mesh' is a file path relative to the scene file or shape:NAME (tools/scenes/ has examples; docs/scenes.md "
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
