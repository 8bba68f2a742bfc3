// `physarum sketch`'s work (api/sketch/sketch_run.hpp): the sketch read, placed and planned, the
// generated scene run (with --refine, again), the result measured per region and reported.
#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"
#include "common/base/value_range.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/output/ply_writer.hpp"
#include "common/pattern/pattern_analysis.hpp"
#include "common/sketch/sketch_image.hpp"
#include "api/run/prepared_run.hpp"
#include "api/sketch/sketch_run.hpp"
#include "api/sketch/sketch_colours.hpp"
#include "api/sketch/sketch_picture.hpp"
#include "api/sketch/sketch_plan.hpp"
#include "api/sketch/sketch_layers.hpp"
#include "api/sketch/sketch_report.hpp"
#include "api/sketch/stripe_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

namespace physarum {
namespace {

namespace fs = std::filesystem;

Sketch read_sketch(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension != ".json") return sketch_from_image(path);
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the sketch");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded()) throw InputError(path + ": not valid JSON");
  return sketch_from_json(j, path);
}

// A mesh file named relative to the working directory, as the scene in DIR must name it.
std::string mesh_for_scene(const std::string& mesh) {
  if (mesh.rfind("shape:", 0) == 0) return mesh;
  return fs::absolute(mesh).lexically_normal().string();
}

nlohmann::ordered_json sketch_json(const Sketch& sketch, const SketchAttributes& attributes, const SketchRegions& regions,
                                   const SketchPlan& plan) {
  nlohmann::ordered_json j;
  j["source"] = sketch.source;
  j["window"] = {sketch.window.x(), sketch.window.y()};
  const nlohmann::ordered_json marks = sketch_attributes_json(attributes);
  for (auto it = marks.begin(); it != marks.end(); ++it) j[it.key()] = it.value();
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  const bool stripes = plan.model->stripes;
  for (const RegionAttributes& r : regions.regions) {
    nlohmann::ordered_json region = {
        {"center", {r.center.x(), r.center.y()}},
        {stripes ? "strokes" : "spots", stripes ? r.strokes : r.spots},
        {"filled_from", r.filled_from >= 0 ? nlohmann::ordered_json(r.filled_from) : nlohmann::ordered_json(nullptr)}};
    if (stripes) {
      region["orientation"] = r.orientation, region["width"] = r.width;
    } else {
      region["area"] = r.area, region["aspect"] = r.aspect, region["orientation"] = r.orientation, region["spacing"] = r.spacing;
    }
    list.push_back(region);
  }
  j["regions"] = list;
  j["inverse_map"] = {{"model", plan.model->name},
                      {"coefficient", plan.model->rate_key},
                      {stripes ? "trained_width_m" : "trained_area_m2", {plan.trained_smallest, plan.trained_largest}},
                      {"cross_validated_error", plan.cross_validated_error},
                      {"diffusion_factor", plan.kappa}};
  if (regions.marks) j["surface_marks"] = surface_marks_json(*regions.marks);
  if (stripes) j["inverse_map"]["initiator_segments"] = plan.initiators.size();
  j["inverse_map"]["anisotropy_ratios"] = plan.ratio;
  j["inverse_map"]["rates"] = plan.rate;
  return j;
}

// One run's measures per region: spots' or stripes', as the model grows.
struct Measures {
  std::vector<RegionMeasure> spots;
  std::vector<StripeMeasure> stripes;
};

// One run's result: its measures and the segmentation threshold of its field (a cascade freezes
// what lies above it), and for a second layer, the cascade's measure.
struct LayerRun {
  Measures measures;
  double threshold = 0.0;
  CascadeMeasure cascade;
};

// Runs the scene once in `folder` with the plan's rates and measures the result per region; with a
// cascade, as the second layer on the first's frozen spots.
LayerRun grow_and_measure(const SketchRequest& o, const fs::path& out, const SketchPlan& plan, const SketchRegions& regions,
                          const SketchDomain& domain, const InputMesh& mesh, const Cascade* cascade = nullptr) {
  const InputVertexData<double> rates = scale_map(regions, domain, mesh, plan.rate), ratios = scale_map(regions, domain, mesh, plan.ratio);
  // The direction map's components per face (the map source reads NAME_x, NAME_y, NAME_z).
  std::vector<std::vector<double>> direction(3);
  for (const Eigen::Vector3d& d : direction_map(regions, plan, domain, mesh))
    for (int k = 0; k < 3; ++k) direction[static_cast<size_t>(k)].push_back(d[k]);
  write_fields_ply((out / "sketch_maps.ply").string(), mesh, {PlyField{"rate", rates}, PlyField{"ratio", ratios}},
                   {PlyFaceField{"direction_x", direction[0]}, PlyFaceField{"direction_y", direction[1]},
                    PlyFaceField{"direction_z", direction[2]}},
                   {}, "the sketch's reaction rate and anisotropy ratio per input vertex and spot direction per face");
  // A second layer draws its own noise: the first layer's seed would repeat its noise field.
  nlohmann::ordered_json scene = sketch_scene_json(plan, mesh_for_scene(o.mesh), o.area, o.max_circumradius,
                                                   cascade ? o.seed + 1 : o.seed, "sketch_maps.ply");
  if (cascade) make_cascade_scene(scene, *find_reaction_model(plan.model->name), plan.model->field, *cascade);
  write_text_file_atomically((out / "scene.json").string(), scene.dump(2) + "\n");
  RunOptions run;
  run.scene = (out / "scene.json").string();
  run.out = out.string();
  run.backend = o.backend;
  run.device = o.device;
  run.log = o.log;
  if (const RunWritten written = run_to_files(run); written.stopped)
    throw InputError("sketch: the generated run stopped: " + *written.stopped);
  else if (o.log)
    o.log(written.summary);
  const PlyFields ply = read_ply_fields((out / "fields_full.ply").string());
  const std::vector<double>& field = ply.property(plan.model->field);
  std::vector<char> frozen;  // a second layer's: the first layer's spots
  if (cascade)
    frozen = frozen_vertices(read_ply_fields((out / cascade->first_fields).string()).property(plan.model->field),
                             cascade->threshold);
  const PatternAnalysis analysis = analyze_pattern(ply.mesh, InputVertexData<double>(field), {});
  LayerRun result;
  result.threshold = analysis.threshold;
  if (plan.model->stripes) {
    result.measures.stripes = measure_stripes(ply.mesh, field, analysis, regions, domain);
  } else {
    result.measures.spots = measure_regions(analysis, regions, domain, frozen);
  }
  if (cascade) result.cascade = measure_cascade(ply.mesh, field, analysis.threshold, frozen, domain.scale());
  return result;
}

// Each region's relative miss of its size (spot area, or stripe width).
std::vector<double> size_misses(const SketchPlan& plan, const Measures& measures) {
  std::vector<double> misses;
  for (size_t k = 0; k < measures.spots.size(); ++k) misses.push_back(area_miss(measures.spots[k], plan.wanted_area[k]));
  for (size_t k = 0; k < measures.stripes.size(); ++k)
    misses.push_back(width_miss(measures.stripes[k], plan.wanted_width[k]));
  return misses;
}

// The model a sketch drives without --model: spots grow Turing's spots, a sketch of strokes alone
// Meinhardt's stripes.
std::string default_model(const Sketch& sketch) {
  return sketch.spots.empty() && sketch.surface_spots.empty() ? "meinhardt-stripes" : "turing-spots";
}

// A sketch measured, placed on the surface and planned: everything that can refuse it, before any
// output exists.
struct Layer {
  Sketch sketch;
  SketchAttributes attributes;
  SketchRegions regions;
  std::optional<SketchDomain> domain;
  SketchPlan plan;
};

// The layer's regions and where they lie: a region per mark for marks on the surface
// (common/sketch/surface_marks.hpp), else the window's n x n regions on the patch or (--uv) the UV
// layout, each blending only with the regions of its own chart there.
void place_regions(Layer& layer, const SketchRequest& o, const SketchModel& model, const InputMesh& mesh) {
  if (!layer.sketch.surface_spots.empty()) {
    if (o.uv) throw UsageError("--uv: " + layer.sketch.source + "'s marks lie on the surface, not in a UV window");
    layer.regions = surface_regions(std::make_shared<const SurfaceMarks>(place_surface_marks(layer.sketch, mesh)));
    layer.domain = SketchDomain::surface(layer.sketch, mesh, o.area);
    return;
  }
  layer.attributes = measure_sketch(layer.sketch);
  layer.regions = model.stripes ? stroke_regions(layer.sketch, o.regions) : sketch_regions(layer.sketch, layer.attributes, o.regions);
  layer.domain = o.uv ? SketchDomain::uv(layer.sketch, mesh, o.area) : SketchDomain::patch(layer.sketch, mesh, o.area);
  if (o.uv)
    for (const RegionAttributes& r : layer.regions.regions) layer.regions.chart.push_back(layer.domain->chart_at(r.center));
}

Layer prepare_layer(const std::string& path, const SketchRequest& o, const std::string& model_name, const InputMesh& mesh) {
  Layer layer;
  layer.sketch = read_sketch(path);
  const SketchModel& model = sketch_model(model_name.empty() ? default_model(layer.sketch) : model_name);
  if (model.stripes && layer.sketch.strokes.empty())
    throw InputError(layer.sketch.source + ": " + model.name + " grows stripes along strokes, and the sketch has none");
  place_regions(layer, o, model, mesh);
  const SketchDomain& domain = *layer.domain;
  layer.plan = model.stripes ? plan_stripes(layer.regions, domain, model, o.max_circumradius)
                             : plan_sketch(layer.regions, domain, model, o.max_circumradius);
  if (model.stripes) place_initiators(layer.plan, layer.regions, domain, o.seed);
  return layer;
}

// Runs a layer in `folder`, and with --refine K corrects its missed regions' rates and runs again,
// up to K times; each run's rates and misses are appended to `iterations`.
LayerRun grow_refined(const SketchRequest& o, const fs::path& folder, Layer& layer, const InputMesh& mesh,
                      nlohmann::ordered_json& iterations) {
  SketchPlan& plan = layer.plan;
  const double tolerance = plan.model->stripes ? kWidthTolerance : kAreaTolerance;
  for (int iteration = 0;; ++iteration) {
    LayerRun run = grow_and_measure(o, folder, plan, layer.regions, *layer.domain, mesh);
    const std::vector<double> misses = size_misses(plan, run.measures);
    const bool all_pass = std::all_of(misses.begin(), misses.end(), [&](double m) { return std::abs(m) <= tolerance; });
    iterations.push_back({{"rates", plan.rate}, {"steps", plan.steps}, {plan.model->stripes ? "width_misses" : "area_misses", misses}});
    if (all_pass || iteration == o.refine) return run;
    // A region whose pattern came out (1 + miss) times too big needs (1 + miss)^refine_exponent
    // times the rate (SketchPlan::refine_exponent). Regions without a measure keep theirs.
    for (size_t k = 0; k < misses.size(); ++k)
      if (std::isfinite(misses[k])) plan.rate[k] *= std::pow(1.0 + misses[k], plan.refine_exponent);
    plan.steps = static_cast<long long>(std::ceil(plan.model->rate_time / *std::min_element(plan.rate.begin(), plan.rate.end())));
  }
}

// A region's centre in report.json: a mark's point on the surface, or the window centre's.
nlohmann::ordered_json region_center(const SketchRegions& regions, size_t k, const SketchDomain& domain) {
  if (!regions.marks) return center_json(domain, regions.regions[k].center);
  const Eigen::Vector3d& p = regions.marks->point[k];
  return {p.x(), p.y(), p.z()};
}

// sketch.png: the marks as measured, in their window (over the UV layout with --uv), or for marks on
// the surface drawn on the full-resolution mesh of a run in `run_folder`.
RgbImage sketch_picture(const Layer& layer, const SketchRequest& o, const InputMesh& mesh, const fs::path& run_folder) {
  if (!layer.regions.marks) return draw_sketch(layer.sketch, o.uv ? &mesh : nullptr);
  return draw_surface_marks(*layer.regions.marks, read_ply_fields((run_folder / "fields_full.ply").string()).mesh);
}

// report.json's per-region entries of a layer; `passed` counts the regions whose size (spots) or
// orientation (stripes) passed.
nlohmann::ordered_json region_reports(const Layer& layer, const Measures& measures, int& passed) {
  const SketchDomain& domain = *layer.domain;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  const SketchPlan& plan = layer.plan;
  for (size_t k = 0; k < layer.regions.regions.size(); ++k) {
    const RegionAttributes& r = layer.regions.regions[k];
    list.push_back(plan.model->stripes
                       ? stripe_region_report(r, plan.wanted_width[k], measures.stripes[k], domain)
                       : region_report(r, plan.wanted_area[k], r.spacing * region_length_factor(layer.regions, k, domain),
                                       measures.spots[k], region_center(layer.regions, k, domain), domain.scale(),
                                       plan.ratio[k] < 1.0));
    if (layer.regions.marks) {
      // A mark's orientation is its own axis: the sketched angle from it is 0.
      const Eigen::Vector3d& axis = layer.regions.marks->axis[k];
      list.back()["sketched"]["axis"] = {axis.x(), axis.y(), axis.z()};
      // Marks are samples of the pattern placed far apart, not a drawn lattice: their spacing is
      // reported, not judged.
      if (list.back()["verdict"].contains("spacing")) list.back()["verdict"]["spacing"] = "marks: not judged";
    }
    passed += list.back()["verdict"][plan.model->stripes ? "orientation" : "area"] == "pass";
  }
  return list;
}

}  // namespace

std::string run_sketch(const SketchRequest& o) {
  if (o.regions < 1 || o.regions > 16) throw UsageError("--regions " + std::to_string(o.regions) + ": 1 to 16 per side");
  if (o.refine < 0) throw UsageError("--refine must be >= 0");
  // ---- everything that can refuse the input, before any output exists ----
  if (!o.model.empty()) sketch_model(o.model);
  const InputMesh mesh = load_mesh(o.mesh);
  Layer first = prepare_layer(o.sketch, o, o.model, mesh);
  const SketchModel& model = *first.plan.model;
  std::optional<Layer> second;
  if (!o.layer2.empty()) {
    if (model.stripes) throw InputError("--layer2: a second layer grows spots between the first's; " + model.name + " takes none");
    second = prepare_layer(o.layer2, o, model.name, mesh);
    if (second->sketch.window != first.sketch.window)
      throw InputError(o.layer2 + ": its window differs from " + o.sketch + "'s: the two layers must share one window");
  }

  const std::vector<ColorMapSettings> colour_sets = read_colour_sets(o.colors);
  if (colour_sets.size() == 2 && !second) throw UsageError("--colors: a second colour set is for a second layer (--layer2)");

  create_output_folder(o.out);
  const fs::path out(o.out);

  nlohmann::ordered_json iterations = nlohmann::ordered_json::array(), report;
  // With a second layer, the first runs in DIR/layer1 and the second, on its frozen spots, in DIR.
  const fs::path first_folder = second ? out / "layer1" : out;
  if (second) create_output_folder(first_folder.string());
  const LayerRun run = grow_refined(o, first_folder, first, mesh, iterations);
  write_rgb_png((out / "sketch.png").string(), sketch_picture(first, o, mesh, first_folder));
  int passed = 0;
  report["regions"] = region_reports(first, run.measures, passed);
  report["iterations"] = iterations;
  nlohmann::ordered_json sketch_file = sketch_json(first.sketch, first.attributes, first.regions, first.plan);
  if (second) {
    write_rgb_png((out / "sketch_layer2.png").string(), sketch_picture(*second, o, mesh, first_folder));
    const Cascade cascade{"layer1/fields_full.ply", run.threshold, o.rosettes};
    const LayerRun top = grow_and_measure(o, out, second->plan, second->regions, *second->domain, mesh, &cascade);
    int passed2 = 0;
    report["layer2"] = cascade_json(top.cascade, o.rosettes);
    report["layer2"]["regions"] = region_reports(*second, top.measures, passed2);
    sketch_file["layer2"] = sketch_json(second->sketch, second->attributes, second->regions, second->plan);
  }
  if (!colour_sets.empty()) {
    const ColorMapSettings& top_set = colour_sets.back();  // SET2, or SET1 for both layers
    write_layer_colours(first_folder, model.field, colour_sets.front());
    if (second) write_layer_colours(out, model.field, top_set, FirstLayerColours{first_folder, run.threshold}, colour_sets.front());
  }
  write_text_file_atomically((out / "sketch.json").string(), sketch_file.dump(2) + "\n");
  write_text_file_atomically((out / "report.json").string(), report.dump(2) + "\n");
  std::ostringstream line;
  line << "physarum sketch: " << model.name << ", " << first.regions.regions.size() << " regions, " << iterations.size()
       << " run(s); "
       << (model.stripes ? "stripe orientation within " + ValueRange::number(kStripeOrientationTolerance) + " degrees"
                         : "spot area within " + ValueRange::number(kAreaTolerance * 100) + " %")
       << " of the sketch in " << passed << " of " << first.regions.regions.size() << " regions"
       << (second ? "; a second layer on its frozen spots (report.json's layer2)" : "") << "; wrote " << o.out
       << "/{sketch.png, sketch.json, scene.json, report.json, sketch_maps.ply} beside the run's files";
  return line.str();
}


}  // namespace physarum
