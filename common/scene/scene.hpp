#pragma once
// A simulation scene: the surface, the maps, the run settings, the harness's settings and the model
// it runs (the agent model of Table 1 in SI units, angles in degrees in the file and radians here, or
// a reaction–diffusion system). Read from one flat JSON object whose keys are listed in
// docs/scenes.md; every bad value is an InputError naming the key, the value and the allowed range,
// and an unknown key is an error too.
#include "common/color/color_map_json.hpp"
#include "common/maps/map_definition.hpp"
#include "common/scene/scene_models.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

namespace physarum {

// How the differential harness (`physarum compare`) runs and judges this scene: the run length of
// each seed, the sampling, the metrics' resolution and the equivalence margins. Every key is
// optional in the file (prefix "compare_"); the defaults are the documented ones below. Margins are
// on dimensionless metrics: mean/U, coverage fractions, and band powers and the agent-density
// dispersion relative to the reference arm's mean.
struct ComparisonSettings {
  double burn_in = 2.0;           // s simulated and discarded at the start of every seed
  double duration = 3.0;          // s simulated and averaged after the burn-in
  double sample_interval = 0.1;   // s between two samples of the metrics
  int max_seeds = 64;             // seeds per arm at most: the sequential test's budget
  double margin_mean = 0.03;      // on mean / U
  double margin_coverage = 0.02;  // on each coverage fraction (a fraction of the surface's area)
  double margin_spectrum = 0.3;   // relative, on each spectral band power (harmonic and radial)
  double margin_detail = 0.1;     // relative, on each detail energy
  double margin_density = 0.1;    // relative, on the agent-density dispersion
  int spectrum_bands = 6;         // manifold-harmonic bands (and radial bands on flat domains)
  int eigenpairs = 48;            // manifold harmonics computed for the bands
};

struct Scene {
  std::string source;  // the scene file, for messages ("" when built in code)

  // The model it runs (common/scene/scene_models.hpp): the agent model (paper 000, "model":
  // "physarum", the default), a reaction–diffusion system (paper 002) or one on a growing sheet
  // (paper 003). What the library does with each is its entry in api/models/model_table.cpp.
  SceneModel model;

  // ---- surface ----
  std::string mesh;                        // resolved file path, or "shape:NAME"
  std::optional<double> scale_to_area;     // rescale the input so its area is this many m^2
  std::optional<double> max_circumradius;  // intrinsic refinement bound, in scaled units (m)
  double min_angle_deg = 0.0;              // optional refinement angle bound

  // ---- maps (paper Sec. 3.3), for every model ----
  MapSet maps;                // the named maps ("maps"), parsed and checked, not yet evaluated
  nlohmann::json maps_given;  // "maps" as the file gave it (null when absent), for run.json

  // ---- time ----
  double time_step = 0.0;  // s
  std::uint32_t seed = 1;
  std::optional<long long> steps;   // run length, if the file gives one
  std::optional<double> sim_time;   // s, alternative to steps

  ComparisonSettings comparison;

  // ---- pictures ----
  ColorMapSettings color_map;  // how the result file and preview.png are coloured (default viridis, 0 .. 2U)

  // The agent model's part; std::logic_error on a scene of another model (for the model's own code:
  // everything else asks the table of models).
  AgentModelSpec& agent_model();
  const AgentModelSpec& agent_model() const;
  // The reaction–diffusion system, or nullptr for a scene of another model.
  ReactionDiffusionSpec* reaction_diffusion() { return std::get_if<ReactionDiffusionSpec>(&model); }
  const ReactionDiffusionSpec* reaction_diffusion() const { return std::get_if<ReactionDiffusionSpec>(&model); }
  // The growth model's part, or nullptr.
  const GrowthSpec* growth() const { return std::get_if<GrowthSpec>(&model); }
};

// A growth scene's reaction–diffusion system as a scene of its own (the same surface, maps, time
// step and seed): what builds the system on each state of the growing sheet.
Scene reaction_diffusion_scene(const Scene& growth_scene);

// Parses and validates a scene file. A relative "mesh" path, and the files the maps read, are
// resolved against the scene file's folder.
// `overrides` (scene keys, nested ones as dotted paths: common/scene/scene_overrides.hpp) replaces or adds
// keys of the file before it is read, with the same checks (compare's --arm, run's --set).
Scene load_scene(const std::string& path, const nlohmann::json& overrides = nlohmann::json::object());

// The same from a JSON object built in code (the library and Python's way in): `source` names the
// scene in messages ("" shows "scene") and relative paths resolve against its folder ("": the
// working directory).
Scene scene_from_json(nlohmann::json scene, const std::string& source = "",
                      const nlohmann::json& overrides = nlohmann::json::object());

// Validates a scene built in code (the same checks as load_scene): the values, and that every map a
// parameter or control names exists in scene.maps and is of the kind needed.
void validate_scene(const Scene& scene);

// True for a scene of the agent model (for its own code and guards; the places that handle every
// model ask the table of models, api/models/model_table.hpp).
inline bool is_agent_model(const Scene& scene) { return std::holds_alternative<AgentModelSpec>(scene.model); }

// The model's "model" value ("physarum", "gray_scott", "growth", ...) and its whole description as
// JSON (what a checkpoint's identity covers).
std::string model_key(const Scene& scene);
nlohmann::ordered_json model_json(const Scene& scene);

// The agent model's agent count, 0 for a model without agents (memory estimates, run.json).
inline int agent_count(const Scene& scene) { return is_agent_model(scene) ? scene.agent_model().agents : 0; }

// The agent model's has_parameter_maps / steady_mean_is_U (common/scene/scene_agents.hpp); false
// for a model without agents.
bool has_parameter_maps(const Scene& scene);
bool steady_mean_is_U(const Scene& scene);

}  // namespace physarum
