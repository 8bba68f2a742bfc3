#include "tools/run/run_growth.hpp"

#include "api/session.hpp"
#include "common/base/errors.hpp"
#include "common/output/maps_ply.hpp"
#include "common/output/ply_writer.hpp"
#include "common/output/preview_image.hpp"
#include "common/output/time_lapse.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "tools/run/run_loop.hpp"
#include "tools/run/run_reaction_diffusion.hpp"
#include "tools/run/surface_exports.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace physarum::cli {
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

}  // namespace

int run_growth(const Scene& scene, const RunOptions& o, long long steps, const std::optional<ResumePoint>& resume) {
  const GrowthSpec& spec = *scene.growth();
  TimeLapse time_lapse(o.frames, steps);

  // ---- everything that can reject the input, before any output exists ----
  Session session(scene, session_options(o, steps));
  GrowthSimulation& growth = *session.growth();
  const PreparedSurface& start = session.surface();
  const FullResolutionMesh start_full = build_full_resolution_mesh(start.input, start.domain);
  const std::vector<std::string>& morphogens = session.layer_names();
  const int preview_layer = session.preview_layer();
  if (!o.maps_out.empty()) write_maps_ply(o.maps_out, start.input, maps_on_input(scene.maps, start, session.maps(), o.scene));
  // With a prescribed growth and no reaction steps the morphogens never change: the picture shows
  // where the sheet grew instead.
  const bool show_growth = spec.growth.stretch && spec.schedule.reaction_steps == 0;

  // The layers as written: the preview one first, then the other morphogens, the area growth and the stretch.
  auto layers_now = [&] {
    std::vector<std::pair<std::string, IntrinsicVertexData<double>>> layers;
    const std::vector<IntrinsicVertexData<double>> u = morphogen_layers(growth);
    const IntrinsicVertexData<double> area = growth.area_growth();
    IntrinsicVertexData<double> stretch(area.size());
    for (size_t i = 0; i < area.size(); ++i) stretch[i] = std::sqrt(area[i]);
    if (show_growth) layers.emplace_back("area_growth", area);
    layers.emplace_back(morphogens[static_cast<size_t>(preview_layer)], u[static_cast<size_t>(preview_layer)]);
    for (int m = 0; m < static_cast<int>(morphogens.size()); ++m)
      if (m != preview_layer) layers.emplace_back(morphogens[static_cast<size_t>(m)], u[static_cast<size_t>(m)]);
    if (!show_growth) layers.emplace_back("area_growth", area);
    layers.emplace_back("stretch", stretch);
    return layers;
  };
  auto coloring_of = [&](const auto& shown) { return scene.color_map.mapping(color_unit(shown)); };
  std::vector<FrameMesh> frame_meshes;

  ModelRun model;
  model.fields_file = "morphogens.ply";
  model.fields_description = "growth model: morphogens, area growth and stretch on the grown sheet";
  model.stats_header = "time,growth_step,vertices,rest_area," + morphogen_stats_header(morphogens).substr(5);
  model.stats_row = [&] {
    const GrowingSheet& sheet = growth.sheet();
    std::ostringstream head;
    head.precision(17);
    head << growth.time() << "," << growth.growth_steps_done() << "," << sheet.topology.vertex_count << ","
         << rest_area(sheet.rest);
    const std::string row = morphogen_stats_row(growth.time(), morphogen_layers(growth), growth.surface().domain.vertex_mass);
    return head.str() + row.substr(row.find(','));
  };
  model.frame = [&] {
    const PreparedSurface& now = growth.surface();
    const auto layers = layers_now();
    PreviewOptions preview;
    preview.coloring = coloring_of(layers.front().second);
    FrameMesh kept{now.input, {}};
    for (const auto& [name, values] : layers)
      kept.fields.emplace_back(name, InputVertexData<double>(std::vector<double>(values.begin(), values.end())));
    frame_meshes.push_back(std::move(kept));
    return render_preview(now.input, frame_meshes.back().fields.front().second, preview);
  };
  model.check_end = [&] { check_morphogens_finite(growth, morphogens, scene.source); };
  std::optional<FullResolutionMesh> final_full;
  model.result = [&] {
    ModelResult r;
    r.layers = layers_now();
    r.coloring = coloring_of(r.layers.front().second);
    r.surface = &growth.surface();
    final_full = build_full_resolution_mesh(r.surface->input, r.surface->domain);
    r.full = &*final_full;
    return r;
  };
  model.stopped = [&] { return growth.stopped(); };
  model.write_extra = [&](const std::filesystem::path& out, std::vector<std::string>& written) {
    for (size_t k = 0; k < frame_meshes.size(); ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04zu.ply", k + 1);
      std::vector<PlyField> fields;
      for (const auto& [field, values] : frame_meshes[k].fields) fields.push_back(PlyField{field, values});
      write_fields_ply((out / "frames" / name).string(), frame_meshes[k].mesh, fields, coloring_of(fields.front().values),
                       "growth model: the sheet at a time-lapse frame");
    }
    if (!frame_meshes.empty()) written.push_back("frames/*.ply");
  };
  model.run_json = [&](nlohmann::ordered_json& j, double /*seconds*/) {
    j["model"] = "growth";
    j["morphogens"] = morphogens;
    // The layer the pictures show and the unit its colours count in (what `physarum render` reads).
    const auto shown = layers_now().front();
    j["preview_morphogen"] = shown.first;
    j["color_unit"] = color_unit(shown.second);
    j["time_step"] = scene.time_step;
    j["substeps"] = growth.substeps();
    j["seed"] = scene.seed;
    growth_records_json(j, growth);
    j["initial_vertices"] = start.domain.vertex_count;
    j["growth"] = growth_json(spec);
    if (!scene.maps.empty()) j["maps"] = scene.maps_given;
  };
  model.summary = [&](double seconds) {
    std::ostringstream line;
    line << "growth, " << growth.steps_taken() << " steps (" << growth.growth_steps_done() << " growth steps, "
         << growth.sheet().topology.vertex_count << " vertices, area x" << rest_area(growth.sheet().rest) / growth.initial_rest_area()
         << ") in " << seconds << " s";
    return line.str();
  };
  const std::optional<TexelLocations> no_texture;  // the grown sheet has no UV layout: result.glb carries vertex colours
  return run_and_write(growth, RunSetup{o, scene, steps, resume, start, start_full, no_texture, time_lapse}, model);
}

}  // namespace physarum::cli
