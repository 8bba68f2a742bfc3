#include "api/run/run_loop.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"
#include "common/run/checkpoint.hpp"
#include "common/color/color_map_json.hpp"
#include "common/output/ply_writer.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/surface/field_transfer.hpp"
#include "api/run/run_checkpoints.hpp"
#include "api/run/surface_exports.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

namespace physarum {
namespace {

// About this many rows go into stats.csv, evenly spaced in steps (plus the initial row).
constexpr long long kStatsRows = 100;

// The fields on the input mesh and at full resolution, preview.png, texture and result.glb; appends
// the names written, in order, to `written`.
SurfaceExportsWritten write_fields(const std::filesystem::path& out, const RunSetup& setup, const ModelRun& model,
                                   const ModelResult& result, std::vector<std::string>& written) {
  const PreparedSurface& surface = result.surface ? *result.surface : setup.surface;
  const FullResolutionMesh& full = result.full ? *result.full : setup.full;
  std::vector<InputVertexData<double>> on_input, on_full;
  std::vector<PlyField> input_fields, full_fields;
  on_input.reserve(result.layers.size());
  on_full.reserve(result.layers.size());
  for (const auto& [name, values] : result.layers) {
    on_input.push_back(intrinsic_to_input(surface.input_to_intrinsic, values));
    on_full.push_back(full.vertex_values(values));
    input_fields.push_back(PlyField{name, on_input.back()});
    full_fields.push_back(PlyField{name, on_full.back()});
  }
  write_fields_ply((out / model.fields_file).string(), surface.input, input_fields, result.coloring,
                   model.fields_description + " per input vertex");
  write_fields_ply((out / "fields_full.ply").string(), full.mesh, full_fields, result.coloring,
                   model.fields_description + " per intrinsic vertex (full resolution)");
  PreviewOptions preview;
  preview.coloring = result.coloring;
  if (result.preview) write_rgb_png((out / "preview.png").string(), *result.preview);
  else write_preview_png((out / "preview.png").string(), full.mesh, on_full.front(), preview);
  written.insert(written.end(), {model.fields_file, "fields_full.ply", "preview.png"});
  const SurfaceExportsWritten exports =
      write_surface_exports(out, surface.input, surface.domain, setup.texels, result.layers.front().second,
                            on_input.front(), result.coloring, setup.options.texture, &full.mesh);
  written.insert(written.end(), exports.files.begin(), exports.files.end());
  return exports;
}

// run.json: the run as it went (backend, steps, time, seconds), the model's own keys, the surface,
// what readers of result.glb need and what `physarum render` needs.
nlohmann::ordered_json run_record(const SimulationBackend& simulation, const RunSetup& setup, const ModelRun& model,
                                  long long steps, double seconds, const ModelResult& result,
                                  const GltfExportSummary& glb) {
  const RunOptions& o = setup.options;
  nlohmann::ordered_json j;
  j["backend"] = simulation.backend_name();
  j["backend_requested"] = o.backend;
  j["device"] = simulation.device_name();
  j["steps"] = steps;
  j["sim_time"] = simulation.time();
  j["seconds"] = seconds;
  j["fields_file"] = model.fields_file;
  model.run_json(j, seconds);
  const PreparedSurface& final_surface = result.surface ? *result.surface : setup.surface;
  j["intrinsic_vertices"] = final_surface.domain.vertex_count;
  j["intrinsic_faces"] = final_surface.domain.face_count;
  j["area"] = final_surface.domain.total_area;
  // For readers that check result.glb: its vertex count and the copies made along UV seams.
  j["result_glb_vertices"] = glb.vertices;
  j["result_glb_seam_splits"] = glb.seam_splits;
  j["scene_file"] = o.scene;
  // What `physarum render` needs to rebuild the surface and bake the texture again.
  j["surface"] = surface_spec_json(surface_spec(setup.scene));
  if (setup.texels) j["texture"] = o.texture.to_json();
  // The colours as used: `physarum render` re-colours with them.
  j["colormap"] = color_map_settings_json(setup.scene.color_map);
  return j;
}

}  // namespace

RunLoop::RunLoop(SimulationBackend& simulation, const RunSetup& setup, const ModelRun& model)
    : simulation_(simulation),
      setup_(setup),
      model_(model),
      checkpoints_(std::make_unique<RunCheckpoints>(simulation, setup.options, setup.scene.mesh, setup.scene.time_step,
                                                    setup.steps, setup.resume)),
      next_step_(checkpoints_->first_step()),
      stats_every_(std::max<long long>(1, setup.steps / kStatsRows)),
      last_row_(next_step_ - 1) {
  if (const std::string* resumed = checkpoints_->resumed_stats()) stats_ = *resumed;
  else stats_ = model.stats_header + "\n" + model.stats_row() + "\n";
  checkpoints_->start();
  returned_ = std::chrono::steady_clock::now();
}

RunLoop::~RunLoop() = default;

long long RunLoop::planned_steps() const { return setup_.steps; }
const RunOptions& RunLoop::options() const { return setup_.options; }

bool RunLoop::over() const { return next_step_ > setup_.steps || (model_.stopped && model_.stopped()); }

bool RunLoop::step() {
  if (over()) return false;
  // The caller's time since the last step is not simulation.
  side_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - returned_).count();
  const long long s = next_step_++;
  simulation_.step();
  const bool row = s % stats_every_ == 0 || s == setup_.steps;
  if (row || setup_.time_lapse.due(s)) {
    simulation_.finish();  // the steps enqueued so far count as simulation, not as the reading below
    const auto t = std::chrono::steady_clock::now();
    if (row) {
      stats_ += model_.stats_row() + "\n";
      last_row_ = s;
    }
    if (setup_.time_lapse.due(s)) setup_.time_lapse.add(model_.frame());
    side_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  }
  if (!(model_.stopped && model_.stopped())) checkpoints_->after_step(s, simulation_, stats_, side_seconds_);
  returned_ = std::chrono::steady_clock::now();
  return true;
}

std::string RunLoop::save_state() const {
  CheckpointHeader header = checkpoints_->identity();
  header.step = steps_taken();
  header.run = {{"stats", stats_}, {"last_row", last_row_}, {"seconds", simulation_seconds()}};
  return checkpoint_bytes(header, simulation_.save_state());
}

void RunLoop::restore_state(const std::string& bytes, const std::string& where) {
  const Checkpoint checkpoint = parse_checkpoint(bytes, where);
  check_checkpoint_matches(checkpoint.header, checkpoints_->identity(), where);
  if (checkpoint.header.step > setup_.steps)
    throw InputError(where + ": the state is at step " + std::to_string(checkpoint.header.step) + ", past this run's " +
                     std::to_string(setup_.steps) + " steps");
  std::string stats;
  long long last_row = 0;
  try {
    stats = checkpoint.header.run.at("stats").get<std::string>();
    last_row = checkpoint.header.run.at("last_row").get<long long>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where + ": not a saved run state (" + e.what() + ")");
  }
  simulation_.restore_state(checkpoint.state);
  stats_ = std::move(stats);
  last_row_ = last_row;
  next_step_ = checkpoint.header.step + 1;
}

double RunLoop::simulation_seconds() const {
  // The time since the last step is the caller's, not simulation.
  const double since_last_step = std::chrono::duration<double>(std::chrono::steady_clock::now() - returned_).count();
  return checkpoints_->simulation_seconds(side_seconds_ + since_last_step);
}

RunWritten RunLoop::write(const std::string& folder) {
  simulation_.finish();
  const double seconds = simulation_seconds();
  if (last_row_ != steps_taken()) {
    stats_ += model_.stats_row() + "\n";
    last_row_ = steps_taken();
  }
  if (model_.check_end) model_.check_end();
  const ModelResult result = model_.result();

  create_output_folder(folder);
  const std::filesystem::path out(folder);
  std::vector<std::string> written;
  const SurfaceExportsWritten exports = write_fields(out, setup_, model_, result, written);
  write_text_file_atomically((out / "stats.csv").string(), stats_);
  written.insert(written.end(), {"stats.csv", "run.json"});
  setup_.time_lapse.write(folder);
  if (setup_.time_lapse.enabled()) written.insert(written.end(), {"frames/", "frames.gif"});
  if (model_.write_extra) model_.write_extra(out, written);
  const std::optional<std::string> stopped = model_.stopped ? model_.stopped() : std::nullopt;

  const long long steps = stopped ? simulation_.steps_taken() : steps_taken();
  nlohmann::ordered_json j = run_record(simulation_, setup_, model_, steps, seconds, result, exports.glb);
  if (stopped) j["stopped"] = *stopped;
  checkpoints_->record(j);
  write_text_file_atomically((out / "run.json").string(), j.dump(2) + "\n");
  checkpoints_->remove_file();

  std::string files;
  for (const std::string& name : written) files += (files.empty() ? "" : ", ") + name;
  const RunOptions& o = setup_.options;
  RunWritten done;
  done.summary = "physarum run: " + model_.summary(seconds) + "; wrote " + out.string() + "/{" + files + "}" +
                 (o.maps_out.empty() ? std::string() : " and " + o.maps_out);
  done.stopped = stopped;
  return done;
}

}  // namespace physarum
