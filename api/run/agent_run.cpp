// The agent model's front end of a run (prepare_agent_run in api/run/prepared_run.hpp): what the one
// run loop (api/run/run_loop.hpp) writes for it — pheromone.ply (per species pheromone_0, ... beside
// "pheromone"), stats.csv's columns (time, mean, U, coverages; per species mean_i, U_i), run.json's
// throughput, U and parameters, and pictures coloured in multiples of U (one colour per species).
#include "api/run/prepared_run.hpp"

#include "api/run/surface_exports.hpp"
#include "common/color/color_map_json.hpp"
#include "common/output/preview_image.hpp"
#include "common/scene/scene_json.hpp"
#include "common/setup/agent_inputs.hpp"
#include "common/setup/species_statistics.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/surface/full_resolution_mesh.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace physarum {
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
    std::optional<TexelLocations> texels = texels_for_run(session_.surface().input, domain, o.texture, o.log);
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

}  // namespace physarum
