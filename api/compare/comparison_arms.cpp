#include "api/compare/comparison_arms.hpp"

#include "common/base/errors.hpp"
#include "common/base/overloaded.hpp"
#include "common/setup/agent_inputs.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/setup/reaction_diffusion_build.hpp"
#include "common/harness/reaction_diffusion_metrics.hpp"
#include "common/scene/scene_overrides.hpp"
#include "api/backend_factory.hpp"
#include "api/feasible_surface.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <tuple>

namespace physarum {
namespace {

std::string trim(const std::string& s) {
  const size_t first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// Steps of one seed (burn-in + duration): the run whose work the fail-fast checks estimate.
long long steps_per_seed(const Scene& scene) {
  return std::max<long long>(1, std::llround((scene.comparison.burn_in + scene.comparison.duration) / scene.time_step));
}

auto surface_key(const Scene& s) {
  return std::make_tuple(s.mesh, s.scale_to_area.value_or(-1.0), s.max_circumradius.value_or(-1.0), s.min_angle_deg);
}

std::vector<std::string> names(const std::vector<MetricInfo>& metrics) {
  std::vector<std::string> n;
  for (const MetricInfo& info : metrics) n.push_back(info.name);
  return n;
}

// What the arms' metrics can share: one discretisation, or a common sampling of two triangulations
// of one input surface (or why there is none).
ArmsShare arms_share(const std::vector<Arm>& arms, bool same_discretisation) {
  ArmsShare share;
  share.discretisation = same_discretisation;
  if (same_discretisation) return share;
  if (arms[0].common_sampling_withheld) {
    share.no_sampling = std::string("the planted fault ") + kHarnessFault + " withholds it";
    return share;
  }
  if (same_input_surface(*arms[0].surface, *arms[1].surface, &share.no_sampling))
    share.sampling = std::make_shared<const CommonSampling>(arms[0].surface, arms[1].surface);
  return share;
}

// Agent-model arms: each arm's surface (checked for feasibility, built once where the arms share
// one), its maps and per-vertex parameters evaluated once for all its seeds, and its metrics.
void prepare_agent_model_arms(std::vector<Arm>& arms) {
  // Surfaces, built once where the arms share one, and the maps of each arm's scene on its surface,
  // evaluated once for all its seeds (through the map cache).
  const MapCache cache = MapCache::from_environment();
  std::vector<std::shared_ptr<const SceneArrays>> arrays(arms.size());
  for (size_t i = 0; i < arms.size(); ++i) {
    Arm& a = arms[i];
    for (size_t j = 0; j < i; ++j)
      if (surface_key(arms[j].scene) == surface_key(a.scene)) a.surface = arms[j].surface;
    std::optional<EvaluatedMaps> maps;
    if (!a.surface) {
      FeasibleSurface feasible = prepare_feasible_surface(a.scene, steps_per_seed(a.scene), cache, [](const std::string& line) { std::cerr << line << "\n"; });
      a.surface = std::make_shared<const PreparedSurface>(std::move(feasible.surface));
      maps = std::move(feasible.maps);
    } else {
      maps = cached_evaluate_maps(map_sources_of(a.scene), *a.surface, cache);
    }
    arrays[i] = std::make_shared<const SceneArrays>(scene_arrays(a.scene, *a.surface, *maps));
    a.scene = with_mean_parameters(a.scene, arrays[i]->parameters, a.surface->domain);
    if (steady_mean_is_U(a.scene))
      a.expected_mean_over_U = expected_mean_over_U(a.scene, arrays[i]->parameters, a.surface->domain);
    a.field_levels = std::array<double, 2>{0.0, 2.0 * uniform_steady_state(a.scene, a.surface->domain.total_area)};
  }

  // Metrics, each arm on its own surface; the discretisation-bound ones only where both arms share it.
  const ArmsShare share = arms_share(
      arms,
      arms.size() == 1 || (arms[0].surface == arms[1].surface && arms[0].scene.agent_model().agents == arms[1].scene.agent_model().agents));
  std::vector<std::shared_ptr<const ComparisonMetrics>> metrics(arms.size());
  for (size_t i = 0; i < arms.size(); ++i) {
    if (i > 0 && arms[i].surface == arms[0].surface && arms[i].scene.comparison.eigenpairs == arms[0].scene.comparison.eigenpairs &&
        arms[i].scene.agent_model().parameters[Param::sensor_distance] == arms[0].scene.agent_model().parameters[Param::sensor_distance] &&
        arms[i].scene.comparison.spectrum_bands == arms[0].scene.comparison.spectrum_bands)
      metrics[i] = metrics[0];  // the eigenpairs and smoothers are computed once (run length, dt
                                          // and U are each arm's own: measure_seed)
    else
      metrics[i] = std::make_shared<const ComparisonMetrics>(*arms[i].surface, arms[i].scene, share);
    arms[i].metrics = metrics[i]->metrics();
    arms[i].left_out = metrics[i]->left_out();
    arms[i].measure = [arrays = arrays[i], metrics = metrics[i]](const Arm& arm, const Scene& seeded,
                                                                 const opencl::ComputeContext* compute,
                                                                 IntrinsicVertexData<double>* final_field) {
      const auto sim = make_backend(arm.backend, compute, arm.surface->domain, seeded, *arrays, arm.options);
      return metrics->measure_seed(*sim, seeded, arm.expected_mean_over_U.value_or(1.0), final_field);
    };
  }
}

// Reaction-diffusion arms: the surface (built once where shared) and maps as `physarum run` builds
// them, then per seed the system with that seed's noise and spots. The pattern scale that picks the
// spectral metrics is the continuum system's, taken from the arm judged against, so that two arms
// on different triangulations measure the same metric set.
void prepare_reaction_diffusion_arms(std::vector<Arm>& arms) {
  std::vector<std::shared_ptr<const EvaluatedMaps>> maps(arms.size());
  for (size_t i = 0; i < arms.size(); ++i) {
    Arm& a = arms[i];
    for (size_t j = 0; j < i; ++j)
      if (surface_key(arms[j].scene) == surface_key(a.scene)) a.surface = arms[j].surface;
    if (!a.surface)
      a.surface = std::make_shared<const PreparedSurface>(
          prepare_scene_surface(a.scene, [](const std::string& line) { std::cerr << line << "\n"; }));
    maps[i] = std::make_shared<const EvaluatedMaps>(evaluate_maps(a.scene.maps, *a.surface, a.scene.source));
  }
  const Arm& baseline = arms.back();
  // The kinetics are linearised about the uniform state: each morphogen's area-weighted initial mean
  // (its "initial" where that is a number; a cascade's earlier field otherwise).
  const ReactionDiffusionSystem baseline_system = build_reaction_diffusion_system(baseline.scene, *baseline.surface, *maps.back());
  const IntrinsicVertexData<double>& mass = baseline.surface->domain.vertex_mass;
  std::vector<double> uniform;
  for (const IntrinsicVertexData<double>& initial : baseline_system.initial) {
    double weighted = 0.0, area = 0.0;
    for (size_t v = 0; v < initial.size(); ++v) weighted += mass[v] * initial[v], area += mass[v];
    uniform.push_back(weighted / area);
  }
  const double pattern_scale = reaction_diffusion_pattern_scale(baseline_system, baseline.surface->domain, uniform);

  const ArmsShare share = arms_share(arms, arms.size() == 1 || arms[0].surface == arms[1].surface);
  std::vector<std::shared_ptr<const ReactionDiffusionMetrics>> metrics(arms.size());
  for (size_t i = 0; i < arms.size(); ++i) {
    const ComparisonSettings &c = arms[i].scene.comparison, &c0 = arms[0].scene.comparison;
    if (i > 0 && arms[i].surface == arms[0].surface && c.eigenpairs == c0.eigenpairs && c.spectrum_bands == c0.spectrum_bands &&
        arms[i].scene.reaction_diffusion()->preview_morphogen == arms[0].scene.reaction_diffusion()->preview_morphogen)
      metrics[i] = metrics[0];  // the eigenpairs are computed once
    else
      metrics[i] = std::make_shared<const ReactionDiffusionMetrics>(*arms[i].surface, arms[i].scene, pattern_scale, share);
    arms[i].metrics = metrics[i]->metrics();
    arms[i].left_out = metrics[i]->left_out();
    arms[i].measure = [maps = maps[i], metrics = metrics[i]](const Arm& arm, const Scene& seeded,
                                                             const opencl::ComputeContext* compute,
                                                             IntrinsicVertexData<double>* final_field) {
      const auto sim = make_reaction_diffusion_backend(arm.backend, compute, arm.surface->domain,
                                                       build_reaction_diffusion_system(seeded, *arm.surface, *maps), arm.options);
      return metrics->measure_seed(*sim, seeded, final_field);
    };
  }
}

}  // namespace

ArmSpec parse_arm(const std::string& text) {
  ArmSpec spec;
  spec.label = text;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const size_t eq = item.find('=');
    const std::string key = trim(item.substr(0, eq)), value = eq == std::string::npos ? "" : trim(item.substr(eq + 1));
    if (eq == std::string::npos || key.empty() || value.empty())
      throw UsageError("--arm '" + text + "': expected key=value[,key=value...], got '" + item + "'");
    if (key == "backend") {
      spec.backend = parse_backend_choice(value);
    } else if (key == "device") {
      spec.device = value;
    } else {
      if (spec.scene_overrides.contains(key)) throw UsageError("--arm '" + text + "': key '" + key + "' given twice");
      spec.scene_overrides[key] = parse_scene_value(value);
    }
  }
  if (text.empty()) throw UsageError("--arm: empty (expected key=value[,key=value...])");
  return spec;
}

std::vector<double> Arm::run_seed(int index, const opencl::ComputeContext* stream) const {
  Scene s = scene;
  s.seed = seed(index);
  IntrinsicVertexData<double> final_field;
  std::vector<double> metrics =
      measure(*this, s, stream ? stream : compute ? &*compute : nullptr, fields ? &final_field : nullptr);
  if (fields) fields->add(index, final_field);
  return metrics;
}

std::vector<Arm> make_arms(const ArmsRequest& request) {
  if (!request.arms.empty() && request.arms.size() != 2)
    throw UsageError("--arm: give it exactly twice (the two arms), or not at all (OpenCL against the reference)");
  if (request.arms.size() == 2 && request.arms[0].label == request.arms[1].label)
    throw UsageError("--arm: the two arms are the same ('" + request.arms[0].label + "')");
  const Scene base = load_scene(request.scene_path);
  // The models the harness measures, chosen by a visit the compiler holds to every model: a model
  // without metrics here is refused in one line before anything is built.
  const auto prepare = std::visit(
      overloaded{[](const AgentModelSpec&) { return &prepare_agent_model_arms; },
                 [](const ReactionDiffusionSpec&) { return &prepare_reaction_diffusion_arms; },
                 [&](const GrowthSpec&) -> void (*)(std::vector<Arm>&) {
                   throw InputError(request.scene_path + ": physarum compare measures the agent model and "
                                    "reaction-diffusion; a growth scene's sheet changes shape as it grows, and the "
                                    "harness has no metrics for it (compare its reaction-diffusion as a scene of its own)");
                 }},
      base.model);

  // What each arm simulates.
  std::vector<Arm> arms;
  if (request.arms.empty()) {
    if (!request.reference_only) {
      Arm opencl;
      opencl.label = "opencl";
      opencl.backend = BackendChoice::OpenCL;
      arms.push_back(std::move(opencl));
    }
    Arm reference;
    reference.label = "reference";
    reference.backend = BackendChoice::Reference;
    arms.push_back(std::move(reference));
    for (Arm& a : arms) a.scene = base;
  } else {
    for (const ArmSpec& spec : request.arms) {
      nlohmann::json overrides = spec.scene_overrides;
      // Fig. 10c: another agent count with the deposit rescaled so that U (Eq. 5) stays the same.
      // (A deposit rate given by a map is left as it is: its values are per vertex.)
      if (!is_reaction_diffusion(base) && overrides.contains("agents") && overrides["agents"].is_number_integer() &&
          !overrides.contains("deposit_rate") && !base.agent_model().parameter_maps[static_cast<size_t>(Param::deposit_rate)]) {
        const double agents = overrides["agents"].get<double>();
        if (agents > 0)
          overrides["deposit_rate"] =
              to_file_units(parameter_spec(Param::deposit_rate), base.agent_model().parameters[Param::deposit_rate]) * base.agent_model().agents / agents;
      }
      Arm a;
      a.label = spec.label;
      a.backend = spec.backend.value_or(BackendChoice::OpenCL);
      a.scene = load_scene(request.scene_path, overrides);
      arms.push_back(std::move(a));
    }
  }
  // The second arm, and the reference alone when it is stored, number their seeds as the reference arm does.
  for (size_t i = 0; i < arms.size(); ++i) {
    arms[i].seed_offset = i == 1 || request.reference_only ? kSecondArmSeedOffset : 0;
    arms[i].common_sampling_withheld = request.withhold_common_sampling;
    if (request.keep_fields) arms[i].fields = std::make_shared<SeedFields>();
  }

  prepare(arms);
  if (arms.size() == 2 && names(arms[0].metrics) != names(arms[1].metrics))
    throw InputError("compare: the arms '" + arms[0].label + "' and '" + arms[1].label +
                     "' measure different metric sets (their flatness or spectral reach differs); compare arms "
                     "that differ in discretisation or settings of one surface");

  // Devices.
  for (size_t i = 0; i < arms.size(); ++i) {
    Arm& a = arms[i];
    if (a.backend != BackendChoice::OpenCL) continue;
    const std::string device =
        request.arms.empty() ? request.device : request.arms[i].device.value_or(request.device);
    a.compute = opencl::make_compute_context(device);
    a.options.build_options = request.fault_build_option;
  }
  return arms;
}

}  // namespace physarum
