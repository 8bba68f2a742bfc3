#include "api/run/run_reaction_diffusion.hpp"

#include "common/base/errors.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/output/preview_image.hpp"
#include "common/output/texture_bake.hpp"
#include "api/session.hpp"
#include "api/run/prepared_run.hpp"
#include "api/run/run_loop.hpp"
#include "api/run/surface_exports.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace physarum {
namespace {

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

}  // namespace

// The run diverged when a morphogen is no longer finite: an error, not a result.
void check_morphogens_finite(const SimulationBackend& simulation, const std::vector<std::string>& morphogens,
                             const std::string& source) {
  for (int m = 0; m < simulation.dynamic_layer_count(); ++m)
    for (const double x : simulation.field_values(m))
      if (!std::isfinite(x))
        throw InputError(source + ": morphogen '" + morphogens[static_cast<size_t>(m)] +
                         "' is no longer finite: the run diverged (a smaller time_step, or \"integrator\": \"imex\")");
}

double morphogen_color_unit(const std::vector<double>& values) {
  const double top = values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
  return top > 0.0 ? top / 2.0 : 1.0;
}

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

namespace {

// A reaction-diffusion system's run: its surface, maps and backend, and what it writes.
class ReactionDiffusionRun final : public PreparedRun {
 public:
  ReactionDiffusionRun(const Scene& scene, const RunOptions& o, long long steps, const std::optional<ResumePoint>& resume)
      : PreparedRun(scene, o, steps, resume),
        simulation_(session_.backend()),
        full_(build_full_resolution_mesh(session_.surface().input, session_.surface().domain)) {
    // The maps go through the map cache, as the agent model's: a geodesic distance or a direction
    // field is the slow part of a flower scene's start, and a sweep runs the same maps many times.
    std::optional<TexelLocations> texels =
        texels_for_run(session_.surface().input, session_.surface().domain, o.texture, o.log);
    describe_outputs(steps);
    start(session_.surface(), full_, std::move(texels));
  }

 private:
  std::vector<IntrinsicVertexData<double>> layers() const {
    std::vector<IntrinsicVertexData<double>> all;
    for (int m = 0; m < simulation_.dynamic_layer_count(); ++m) all.push_back(simulation_.field_values(m));
    return all;
  }
  static double color_unit(const IntrinsicVertexData<double>& values) { return morphogen_color_unit(values.values()); }

  // ---- what a reaction-diffusion system writes (the run itself is the one run loop's) ----
  void describe_outputs(long long steps) {
    const Scene& scene = session_.scene();
    const ReactionDiffusionSpec& spec = *scene.reaction_diffusion();
    const std::vector<std::string>& morphogens = session_.layer_names();
    const int preview_layer = session_.preview_layer();
    const int substeps = session_.substeps();
    model_.fields_file = "morphogens.ply";
    model_.fields_description = "morphogens";
    model_.stats_header = morphogen_stats_header(morphogens);
    model_.stats_row = [this] {
      return morphogen_stats_row(simulation_.time(), layers(), session_.surface().domain.vertex_mass);
    };
    model_.frame = [this, &scene, preview_layer] {
      const IntrinsicVertexData<double> values = simulation_.field_values(preview_layer);
      PreviewOptions preview;
      preview.coloring = scene.color_map.mapping(color_unit(values));
      return render_preview(full_.mesh, full_.vertex_values(values), preview);
    };
    model_.check_end = [this, &morphogens, &scene] { check_morphogens_finite(simulation_, morphogens, scene.source); };
    model_.result = [this, &scene, &morphogens, preview_layer] {
      // The preview morphogen first: the colours, the preview and the exports show the first layer.
      ModelResult r;
      r.layers.emplace_back(morphogens[static_cast<size_t>(preview_layer)], simulation_.field_values(preview_layer));
      for (int m = 0; m < static_cast<int>(morphogens.size()); ++m)
        if (m != preview_layer) r.layers.emplace_back(morphogens[static_cast<size_t>(m)], simulation_.field_values(m));
      r.coloring = scene.color_map.mapping(color_unit(r.layers.front().second));
      return r;
    };
    model_.run_json = [this, &scene, &spec, &morphogens, preview_layer, substeps, steps](nlohmann::ordered_json& j,
                                                                                       double seconds) {
      j["model"] = spec.model;
      j["morphogens"] = morphogens;
      j["preview_morphogen"] = spec.preview_morphogen;
      j["time_step"] = scene.time_step;
      j["steps_per_second"] = seconds > 0 ? static_cast<double>(steps) / seconds : 0.0;
      j["integrator"] = integrator_name(spec.integrator);
      j["substeps"] = substeps;
      j["seed"] = scene.seed;
      const std::vector<IntrinsicVertexData<double>> final_layers = layers();
      for (size_t m = 0; m < final_layers.size(); ++m) {
        const auto& u = final_layers[m];
        j["final"][morphogens[m]] = {{"min", *std::min_element(u.begin(), u.end())},
                                     {"max", *std::max_element(u.begin(), u.end())}};
      }
      // What `physarum render` recolours by: the unit the colour map's levels count in (half the
      // preview morphogen's largest value; an agent run's unit is U).
      j["color_unit"] = color_unit(final_layers[static_cast<size_t>(preview_layer)]);
      j["reaction_diffusion"] = reaction_diffusion_json(spec);
      if (!scene.maps.empty()) j["maps"] = scene.maps_given;
    };
    model_.summary = [this, &spec, substeps, steps](double seconds) {
      std::ostringstream line;
      line << spec.model << ", " << steps << " steps (" << simulation_.time() << " s simulated, " << substeps
           << " sub-step" << (substeps > 1 ? "s" : "") << " each) in " << seconds << " s";
      return line.str();
    };
  }

  SimulationBackend& simulation_;
  const FullResolutionMesh full_;
};

}  // namespace

std::unique_ptr<PreparedRun> prepare_reaction_diffusion_run(const Scene& scene, const RunOptions& options,
                                                            long long steps, const std::optional<ResumePoint>& resume) {
  return std::make_unique<ReactionDiffusionRun>(scene, options, steps, resume);
}

}  // namespace physarum
