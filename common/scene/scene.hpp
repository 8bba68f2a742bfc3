#pragma once
// A simulation scene: the surface, the run settings and every model parameter of Table 1 of the
// paper, in SI units (angles in degrees in the file, radians here). Read from one flat JSON object
// whose keys are listed in the README; every bad value is an InputError naming the key, the value and
// the allowed range, and an unknown key is an error too.
#include "common/color/color_map_json.hpp"
#include "common/maps/map_definition.hpp"
#include "common/model/diffusion_decay.hpp"
#include "common/model/model_parameters.hpp"
#include "common/scene/scene_controls.hpp"
#include "common/scene/scene_reaction_diffusion.hpp"
#include "common/scene/scene_species.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>

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

  // ---- field model ----
  // Set when "model" is a reaction-diffusion system (common/scene/scene_reaction_diffusion.hpp); then the
  // agent model's keys (agents, its parameters, the controls, species) are not used and may not be
  // given. Empty: the agent model ("physarum", the default).
  std::optional<ReactionDiffusionSpec> reaction_diffusion;

  // ---- surface ----
  std::string mesh;                        // resolved file path, or "shape:NAME"
  std::optional<double> scale_to_area;     // rescale the input so its area is this many m^2
  std::optional<double> max_circumradius;  // intrinsic refinement bound, in scaled units (m)
  double min_angle_deg = 0.0;              // optional refinement angle bound

  int agents = 0;  // N (with "species": the sum of the species' agents)
  // Every model parameter of Table 1 (common/model/model_parameters.hpp), in SI units. A parameter given
  // by a map (parameter_maps[p] set) holds NaN here until the surface exists: its values are per
  // vertex (common/setup/scene_maps.hpp: vertex_parameters, and with_mean_parameters for one summary value).
  ParameterValues parameters;
  std::array<std::optional<ParameterMap>, kParamCount> parameter_maps;

  // ---- maps and controls (paper Sec. 3.3) ----
  MapSet maps;                // the named maps ("maps"), parsed and checked, not yet evaluated
  nlohmann::json maps_given;  // "maps" as the file gave it (null when absent), for run.json
  SceneControls controls;
  SceneSpecies species;       // "species" and "sensing" (competing species); empty: one population
  Integrator integrator = Integrator::Forward;  // for the pheromone PDE (Eq. 6 / 7)

  // ---- time ----
  double time_step = 0.0;  // s
  std::uint32_t seed = 1;
  std::optional<long long> steps;   // run length, if the file gives one
  std::optional<double> sim_time;   // s, alternative to steps

  ComparisonSettings comparison;

  // ---- pictures ----
  ColorMapSettings color_map;  // how pheromone.ply and preview.png are coloured (default viridis, 0 .. 2U)
};

// Parses and validates a scene file. A relative "mesh" path, and the files the maps read, are
// resolved against the scene file's folder.
// `overrides` (scene keys, nested ones as dotted paths: common/scene/scene_overrides.hpp) replaces or adds
// keys of the file before it is read, with the same checks (compare's --arm, run's --set).
Scene load_scene(const std::string& path, const nlohmann::json& overrides = nlohmann::json::object());

// Validates a scene built in code (the same checks as load_scene): the values, and that every map a
// parameter or control names exists in scene.maps and is of the kind needed.
void validate_scene(const Scene& scene);

// True for a reaction-diffusion scene (scene.reaction_diffusion set).
inline bool is_reaction_diffusion(const Scene& scene) { return scene.reaction_diffusion.has_value(); }

// True when some model parameter is given by a map.
bool has_parameter_maps(const Scene& scene);

// True when the pheromone's steady mean is U (Eq. 5) for this scene: U counts the deposits of N
// agents at a uniform deposit rate and active fraction against a uniform decay, so it holds with any
// maps on the other parameters, read-stimuli, spawn weights and a bias, but not with a mapped
// deposit_rate, decay_rate, mean_lifetime (sinks included) or activation_time, with write-stimuli
// (pheromone not from agents), with a terminating boundary (lifetimes cut short), or with species
// (each layer's mean is its own species' U instead).
bool steady_mean_is_U(const Scene& scene);

}  // namespace physarum
