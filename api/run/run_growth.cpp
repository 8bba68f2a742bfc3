// `physarum run` for a growth scene (common/scene/scene_growth.hpp, paper 003; prepare_growth_run in
// api/run/prepared_run.hpp): the same command, flags, run loop (api/run/run_loop.hpp) and file
// names as for a reaction–diffusion scene, on the sheet as it has grown (api/growth_simulation.hpp):
//   DIR/morphogens.ply, DIR/fields_full.ply   the grown, deformed sheet (its own vertices: the two
//                         files hold the same mesh) with every morphogen, "area_growth" (rest area
//                         now / at the start, per vertex) and "stretch" (its square root: the linear
//                         growth) as float vertex properties; the colours are the preview morphogen's
//   DIR/preview.png, DIR/result.glb   the grown shape coloured by the preview morphogen, or by the
//                         area growth when the growth is prescribed and nothing reacts
//   DIR/stats.csv         time, growth_step, vertices, rest_area, then each morphogen's area-weighted
//                         mean and variance on the rest metric
//   DIR/run.json          growth_steps, area_growth, newton_iterations (per growth step), energy,
//                         vertices (per growth step), the growth records, the spec as run
//   with --frames K: DIR/frames/frame_NNNN.png and .ply (the sheet at that frame) and DIR/frames.gif.
// A growth step whose equilibrium solve fails stops the run: the outputs are written for the last
// converged sheet, the error says which step and what to change, and the exit status is 1.
#include "api/run/prepared_run.hpp"

#include "api/session.hpp"
#include "common/base/errors.hpp"
#include "common/output/ply_writer.hpp"
#include "common/output/preview_image.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "api/run/run_loop.hpp"
#include "api/run/run_reaction_diffusion.hpp"
#include "api/run/surface_exports.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace physarum {
namespace {

std::vector<IntrinsicVertexData<double>> morphogen_layers(const SimulationBackend& simulation) {
  std::vector<IntrinsicVertexData<double>> all;
  for (int m = 0; m < simulation.dynamic_layer_count(); ++m) all.push_back(simulation.field_values(m));
  return all;
}

// Colours over 0 .. the layer's largest value, as a reaction–diffusion run colours its preview morphogen.
template <class Values>
double color_unit(const Values& values) {
  return morphogen_color_unit(values.values());
}

// A frame's sheet, kept until the outputs are written (as the time-lapse keeps its pictures).
struct FrameMesh {
  InputMesh mesh;
  std::vector<std::pair<std::string, InputVertexData<double>>> fields;
};

// run.json's growth keys: the growth steps done, the area growth, per step the Newton iterations
// and vertices, the final energy, where the time went, and every step's record.
void growth_records_json(nlohmann::ordered_json& j, const GrowthSimulation& growth) {
  const std::vector<GrowthStepRecord>& records = growth.records();
  j["growth_steps"] = growth.growth_steps_done();
  const double area_now = rest_area(growth.sheet().rest);
  j["area_growth"] = area_now / growth.initial_rest_area();
  j["initial_rest_area"] = growth.initial_rest_area();
  j["rest_area"] = area_now;
  nlohmann::ordered_json iterations = nlohmann::ordered_json::array(), vertices = nlohmann::ordered_json::array(),
                         steps_json = nlohmann::ordered_json::array();
  double shell_seconds = 0.0;
  for (const GrowthStepRecord& r : records) {
    iterations.push_back(r.newton_iterations);
    vertices.push_back(r.vertices);
    shell_seconds += r.seconds;
    steps_json.push_back({{"growth_step", r.growth_step}, {"splits", r.splits}, {"vertices", r.vertices},
                          {"faces", r.faces}, {"newton_iterations", r.newton_iterations},
                          {"factorizations", r.factorizations}, {"pieces", r.pieces}, {"residual", r.residual},
                          {"membrane_energy", r.membrane_energy}, {"bending_energy", r.bending_energy},
                          {"rest_area", r.rest_area}, {"seconds", r.seconds}});
  }
  j["newton_iterations"] = iterations;
  j["vertices"] = vertices;
  if (!records.empty())
    j["energy"] = {{"membrane", records.back().membrane_energy}, {"bending", records.back().bending_energy},
                   {"total", records.back().membrane_energy + records.back().bending_energy}};
  // Where the time went: the growth steps (the shell's solves) and the reaction–diffusion steps.
  j["growth_seconds"] = shell_seconds;
  j["reaction_seconds"] = growth.reaction_seconds();
  j["growth_records"] = steps_json;
}


// The growth model's run: the sheet's session, and what it writes on the grown sheet.
class GrowthRun final : public PreparedRun {
 public:
  GrowthRun(const Scene& scene, const RunOptions& o, long long steps, const std::optional<ResumePoint>& resume)
      : PreparedRun(scene, o, steps, resume),
        growth_(*session_.growth()),
        start_full_(build_full_resolution_mesh(session_.surface().input, session_.surface().domain)) {
    const GrowthSpec& spec = *scene.growth();
    // With a prescribed growth and no reaction steps the morphogens never change: the picture shows
    // where the sheet grew instead.
    show_growth_ = spec.growth.stretch && spec.schedule.reaction_steps == 0;
    describe_outputs();
    // The grown sheet has no UV layout: result.glb carries vertex colours.
    start(session_.surface(), start_full_, std::nullopt);
  }

 private:
  // The layers as written: the preview one first, then the other morphogens, the area growth and the stretch.
  std::vector<std::pair<std::string, IntrinsicVertexData<double>>> layers_now() const {
    const std::vector<std::string>& morphogens = session_.layer_names();
    const int preview_layer = session_.preview_layer();
    std::vector<std::pair<std::string, IntrinsicVertexData<double>>> layers;
    const std::vector<IntrinsicVertexData<double>> u = morphogen_layers(growth_);
    const IntrinsicVertexData<double> area = growth_.area_growth();
    IntrinsicVertexData<double> stretch(area.size());
    for (size_t i = 0; i < area.size(); ++i) stretch[i] = std::sqrt(area[i]);
    if (show_growth_) layers.emplace_back("area_growth", area);
    layers.emplace_back(morphogens[static_cast<size_t>(preview_layer)], u[static_cast<size_t>(preview_layer)]);
    for (int m = 0; m < static_cast<int>(morphogens.size()); ++m)
      if (m != preview_layer) layers.emplace_back(morphogens[static_cast<size_t>(m)], u[static_cast<size_t>(m)]);
    if (!show_growth_) layers.emplace_back("area_growth", area);
    layers.emplace_back("stretch", stretch);
    return layers;
  }
  template <class Values>
  ColorMapping coloring_of(const Values& shown) const {
    return session_.scene().color_map.mapping(color_unit(shown));
  }

  void describe_outputs() {
    const Scene& scene = session_.scene();
    const GrowthSpec& spec = *scene.growth();
    const std::vector<std::string>& morphogens = session_.layer_names();
    model_.fields_file = "morphogens.ply";
    model_.fields_description = "growth model: morphogens, area growth and stretch on the grown sheet";
    model_.stats_header = "time,growth_step,vertices,rest_area," + morphogen_stats_header(morphogens).substr(5);
    model_.stats_row = [this] {
      const GrowingSheet& sheet = growth_.sheet();
      std::ostringstream head;
      head.precision(17);
      head << growth_.time() << "," << growth_.growth_steps_done() << "," << sheet.topology.vertex_count << ","
           << rest_area(sheet.rest);
      const std::string row =
          morphogen_stats_row(growth_.time(), morphogen_layers(growth_), growth_.surface().domain.vertex_mass);
      return head.str() + row.substr(row.find(','));
    };
    model_.frame = [this] {
      const PreparedSurface& now = growth_.surface();
      const auto layers = layers_now();
      PreviewOptions preview;
      preview.coloring = coloring_of(layers.front().second);
      FrameMesh kept{now.input, {}};
      for (const auto& [name, values] : layers)
        kept.fields.emplace_back(name, InputVertexData<double>(std::vector<double>(values.begin(), values.end())));
      frame_meshes_.push_back(std::move(kept));
      return render_preview(now.input, frame_meshes_.back().fields.front().second, preview);
    };
    model_.check_end = [this, &morphogens, &scene] { check_morphogens_finite(growth_, morphogens, scene.source); };
    model_.result = [this] {
      ModelResult r;
      r.layers = layers_now();
      r.coloring = coloring_of(r.layers.front().second);
      r.surface = &growth_.surface();
      final_full_ = build_full_resolution_mesh(r.surface->input, r.surface->domain);
      r.full = &*final_full_;
      return r;
    };
    model_.stopped = [this] { return growth_.stopped(); };
    model_.write_extra = [this](const std::filesystem::path& out, std::vector<std::string>& written) {
      for (size_t k = 0; k < frame_meshes_.size(); ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04zu.ply", k + 1);
        std::vector<PlyField> fields;
        for (const auto& [field, values] : frame_meshes_[k].fields) fields.push_back(PlyField{field, values});
        write_fields_ply((out / "frames" / name).string(), frame_meshes_[k].mesh, fields,
                         coloring_of(fields.front().values), "growth model: the sheet at a time-lapse frame");
      }
      if (!frame_meshes_.empty()) written.push_back("frames/*.ply");
    };
    model_.run_json = [this, &scene, &spec, &morphogens](nlohmann::ordered_json& j, double /*seconds*/) {
      j["model"] = "growth";
      j["morphogens"] = morphogens;
      // The layer the pictures show and the unit its colours count in (what `physarum render` reads).
      const auto shown = layers_now().front();
      j["preview_morphogen"] = shown.first;
      j["color_unit"] = color_unit(shown.second);
      j["time_step"] = scene.time_step;
      j["substeps"] = growth_.substeps();
      j["seed"] = scene.seed;
      growth_records_json(j, growth_);
      j["initial_vertices"] = session_.surface().domain.vertex_count;
      j["growth"] = growth_json(spec);
      if (!scene.maps.empty()) j["maps"] = scene.maps_given;
    };
    model_.summary = [this](double seconds) {
      std::ostringstream line;
      line << "growth, " << growth_.steps_taken() << " steps (" << growth_.growth_steps_done() << " growth steps, "
           << growth_.sheet().topology.vertex_count << " vertices, area x"
           << rest_area(growth_.sheet().rest) / growth_.initial_rest_area() << ") in " << seconds << " s";
      return line.str();
    };
  }

  GrowthSimulation& growth_;
  const FullResolutionMesh start_full_;
  bool show_growth_ = false;
  std::vector<FrameMesh> frame_meshes_;  // a frame's sheet, kept until the outputs are written
  std::optional<FullResolutionMesh> final_full_;
};

}  // namespace

std::unique_ptr<PreparedRun> prepare_growth_run(const Scene& scene, const RunOptions& options, long long steps,
                                                const std::optional<ResumePoint>& resume) {
  return std::make_unique<GrowthRun>(scene, options, steps, resume);
}

}  // namespace physarum
