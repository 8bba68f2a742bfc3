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
#include "api/run/prepared_run.hpp"
#include "common/base/errors.hpp"
#include "common/run/checkpoint.hpp"
#include "common/scene/scene.hpp"
#include "tools/commands.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <unistd.h>

namespace physarum::cli {
namespace {

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

// The run with a progress bar on a terminal, its notes on stderr and its closing line on stdout.
int run_simulation(RunOptions o, const std::optional<ResumePoint>& resume) {
  check_run_options(o);
  o.log = [](const std::string& line) { std::cerr << line << "\n"; };
  std::optional<ProgressBar> progress;
  const RunWritten written = run_to_files(o, resume, [&](long long done, long long total) {
    if (!progress) progress.emplace(total);
    progress->update(done);
  });
  std::cout << written.summary << "\n";
  if (written.stopped) std::cerr << "physarum: error: " << *written.stopped << "\n";
  return written.exit_code();
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
