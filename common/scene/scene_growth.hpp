#pragma once
// The growth model's part of a scene (paper 003, docs/growth.md): a reaction–diffusion system on a
// sheet that grows, the sheet's material, how it grows, when, and how it keeps its resolution.
//
//   "model": "growth"
//   "reaction_diffusion": {...}   the keys of a reaction–diffusion scene (model — default gray-scott
//                                 with the paper's start: u = 1, v = 0 but for a seed —, parameters,
//                                 morphogens, initial, dirichlet, preview_morphogen, integrator and
//                                 time_step — which may also stay at the top level)
//   "shell": {"thickness", "young_modulus", "poisson_ratio", "perturbation", "tolerance", "max_iterations"}
//   "growth": {"function": "polynomial"|"exponential", "m", "n", "gamma", "lambda", "rate",
//              "a": MORPHOGEN, "b": MORPHOGEN}                   growth driven by the pattern (Eqs. 6–7)
//          or {"stretch": SCALAR_MAP or number}                  prescribed: the target length stretch
//             plus, for either, "anisotropy": {"direction": VECTOR_MAP, "across": r}
//   "schedule": {"reaction_steps": N, "growth_steps": G, "interleaved": false}
//   "refine": {"max_edge": L}     rest edges longer than L (metres) are split after each growth step
//   "dilute": false               concentrations scaled by old / new rest mass after each growth step
#include "common/growth/growth_law.hpp"
#include "common/maps/map_definition.hpp"
#include "common/scene/model_tag.hpp"
#include "common/scene/scene_reaction_diffusion.hpp"
#include "common/shell/shell_equilibrium.hpp"
#include "common/shell/shell_material.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace physarum {

struct ShellSpec {
  ShellMaterial material;
  // The out-of-plane nudge before each growth step (common/shell/sheet_perturbation.hpp), as a
  // fraction of the mean rest edge length.
  double perturbation = 1e-3;
  // Newton's stopping rule: a residual strain of 1e-8 (the library's default 1e-10 sits near the
  // rounding floor of a sheet of some thousand vertices, where a solve can stall a factor above it).
  NewtonSettings newton{100, 1e-8};
};

struct GrowthAnisotropySpec {
  std::string direction;  // a vector map: the direction of the growth "along"
  // The growth across the direction as a fraction of the growth along it: a face grows by 1 + x
  // along and 1 + across * x across (0: only along; 1: isotropic).
  double across = 0.0;
};

struct GrowthRuleSpec {
  // Pattern-driven growth (Eqs. 6–7) of the faces' mean concentrations of morphogens a and b ...
  GrowthLaw law;
  std::string a, b;  // morphogen names (default: the system's first and second)
  // ... or prescribed: the target isotropic stretch of rest lengths at each point, reached in equal
  // factors over the growth steps (stretch^(1/G) per step).
  std::optional<MapOperand> stretch;
  std::optional<GrowthAnisotropySpec> anisotropy;
};

struct GrowthSchedule {
  long long reaction_steps = 0;  // RD steps (before all growth, or before each growth step when interleaved)
  int growth_steps = 1;
  bool interleaved = false;

  // The run's steps: each RD step and each growth step is one step of `physarum run`.
  long long total_steps() const;
  // Whether run step s (1-based) is a growth step.
  bool is_growth_step(long long s) const;
};

struct GrowthSpec {
  ReactionDiffusionSpec reaction;
  ShellSpec shell;
  GrowthRuleSpec growth;
  GrowthSchedule schedule;
  std::optional<double> max_edge;  // refinement bound on rest edge lengths (m); none: no refinement
  bool dilute = false;
};

// The top-level keys only a growth scene takes.
const std::vector<std::string>& growth_keys();

// Moves "time_step" and "integrator" given inside "reaction_diffusion" to the top level where the
// shared readers look for them (InputError when given in both places). Leaves other scenes alone.
void hoist_growth_time_keys(nlohmann::json& scene, const std::string& source);

// nullopt unless "model" is "growth"; InputError naming the key for anything wrong (the reaction–
// diffusion keys at the top level, an unknown field, a value out of range, a morphogen the system
// does not have).
std::optional<GrowthSpec> read_growth(const nlohmann::json& scene, const std::string& source);

// The maps named exist and are of the right kind (a scalar stretch, a vector direction); the
// reaction–diffusion part's own checks.
void validate_growth(const GrowthSpec& spec, const MapSet& maps, const std::string& source);

// The spec as run.json shows it.
nlohmann::ordered_json growth_json(const GrowthSpec& spec);

// The scene layer's names for the above (common/scene/scene_models.hpp).
struct Scene;
inline std::optional<GrowthSpec> read_model(ModelTag<GrowthSpec>, const nlohmann::json& scene, const std::string& source) {
  return read_growth(scene, source);
}
inline std::string model_key(const GrowthSpec&) { return "growth"; }
inline bool compares_over_its_run_length(const GrowthSpec&) { return true; }  // its reaction's time scale
inline void validate_model(const GrowthSpec& spec, const MapSet& maps, const std::string& source) {
  validate_growth(spec, maps, source);
}
inline nlohmann::ordered_json model_json(const GrowthSpec& spec, const Scene&) { return growth_json(spec); }

}  // namespace physarum
