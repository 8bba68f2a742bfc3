#pragma once
// The one run loop of `physarum run`, for every model: checkpoints and where the run starts, the
// timed loop (statistics rows, time-lapse frames, checkpoints, the progress bar with its ETA), the
// end-of-run checks, and the outputs every model writes the same way (the fields on the input mesh
// and at full resolution, preview.png, texture and result.glb, stats.csv, the time-lapse, run.json,
// the closing line). What differs between models is described by a ModelRun: its layers and their
// names, the colouring, its statistics columns, its run.json keys and its end-of-run checks.
#include "common/color/color_mapping.hpp"
#include "common/output/preview_image.hpp"
#include "common/output/texture_bake.hpp"
#include "common/output/time_lapse.hpp"
#include "common/scene/scene.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/surface/prepared_surface.hpp"
#include "api/run/resume_point.hpp"
#include "api/run/run_options.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <memory>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace physarum {

// A model's layers at the end of a run, as the output files hold them.
struct ModelResult {
  // (property name, values per intrinsic vertex); the first is the one the colours, preview.png,
  // texture.png and result.glb show.
  std::vector<std::pair<std::string, IntrinsicVertexData<double>>> layers;
  ColorMapping coloring;
  // The preview when the model draws its own (competing species: one colour per species); else
  // preview.png shows the first layer through `coloring`.
  std::optional<RgbImage> preview;
  // The surface the layers lie on when the model changed it as it ran (the growth model's sheet:
  // every output is on it); null: the run's surface (RunSetup).
  const PreparedSurface* surface = nullptr;
  const FullResolutionMesh* full = nullptr;
};

// What one model's run writes, for the run loop.
struct ModelRun {
  std::string fields_file;         // the result on the input mesh: "pheromone.ply", "morphogens.ply"
  std::string fields_description;  // the PLY files' comment, e.g. "pheromone"
  std::string stats_header;        // stats.csv's first line
  std::function<std::string()> stats_row;  // a row for the state now
  std::function<RgbImage()> frame;         // a time-lapse frame of the state now
  std::function<void()> check_end;         // after the last step; throws InputError (e.g. divergence)
  std::function<ModelResult()> result;     // the layers to write, after the checks
  // The model's own run.json keys (the loop writes backend, device, steps, sim_time, seconds, the
  // surface, the texture, the colour map and the checkpoints around them).
  std::function<void(nlohmann::ordered_json& run_json, double seconds)> run_json;
  // The model's part of the closing line, e.g. "300 steps (3 s simulated) in 1.2 s, ...".
  std::function<std::string(double seconds)> summary;
  // Optional: why the model stopped before the last step (the loop stops too, writes what the model
  // holds, then prints this and exits with 1); nullopt while it runs on.
  std::function<std::optional<std::string>()> stopped;
  // Optional: files of the model's own, written after the others (the growth model's frame meshes);
  // appends their names to `written`.
  std::function<void(const std::filesystem::path& out, std::vector<std::string>& written)> write_extra;
};

// Everything the loop runs on, prepared by the model's front end before any output exists.
struct RunSetup {
  const RunOptions& options;
  const Scene& scene;  // the mesh and time step identify checkpoints
  long long steps = 0;
  const std::optional<ResumePoint>& resume;
  const PreparedSurface& surface;
  const FullResolutionMesh& full;
  const std::optional<TexelLocations>& texels;
  TimeLapse& time_lapse;  // built (and its --frames checked) before the surface
};

class RunCheckpoints;  // api/run/run_checkpoints.hpp

// What RunLoop::write reports, for its caller to show: the closing line ("physarum run: 300 steps
// ... ; wrote out/{...}") and, when the model stopped before the last step, why (the outputs hold
// what it reached; `physarum run` prints it as an error and exits with 1).
struct RunWritten {
  std::string summary;
  std::optional<std::string> stopped;
  int exit_code() const { return stopped ? 1 : 0; }
};

// The one run loop, a step at a time: `physarum run` runs it to the end (tools/run/command_run.cpp); the Python
// module's Simulation steps it as its caller asks and writes when asked. Both give the same
// statistics rows, frames, checkpoints and files for the same steps.
class RunLoop {
 public:
  // Restores a resumed run's checkpoint (setup.resume) and takes stats.csv's first row.
  RunLoop(SimulationBackend& simulation, const RunSetup& setup, const ModelRun& model);
  ~RunLoop();

  // The next step of the run and what is due after it: a statistics row, a time-lapse frame, a
  // checkpoint. False, taking no step, once the run is over (its last step taken, or the model stopped).
  bool step();
  long long steps_taken() const { return next_step_ - 1; }
  long long planned_steps() const;
  const RunOptions& options() const;
  bool over() const;
  // The seconds spent in step() simulating (statistics rows and frames left out; a resumed run's
  // seconds before its checkpoint included).
  double simulation_seconds() const;
  // stats.csv's text so far (its header and every row taken).
  const std::string& statistics() const { return stats_; }
  // The run's whole state now as checkpoint bytes (common/run/checkpoint.hpp: the backend's state, the
  // steps taken, the statistics text), and back: restore_state refuses (InputError naming `where`) the
  // state of another build, backend, device or scene, or corrupted bytes, and changes nothing then.
  std::string save_state() const;
  void restore_state(const std::string& bytes, const std::string& where);
  // Ends the run where it stands and writes every output into `folder` (options().out for the command
  // line). A run written before its last step records the steps taken and closes stats.csv with a row.
  RunWritten write(const std::string& folder);

 private:
  SimulationBackend& simulation_;
  const RunSetup& setup_;
  const ModelRun& model_;
  std::unique_ptr<RunCheckpoints> checkpoints_;
  std::string stats_;
  long long next_step_ = 1, stats_every_ = 1, last_row_ = 0;
  double side_seconds_ = 0.0;  // statistics rows, frames and the caller's time between steps
  std::chrono::steady_clock::time_point returned_;
};

}  // namespace physarum
