// The agent model's harness (api/compare/comparison_model.hpp): its arms measured by
// common/harness/comparison_metrics.hpp, its planted faults (opencl/planted_faults.hpp, the ones not
// named rd-*), stored reference statistics, and Fig. 10c's agent-count arms.
#include "api/compare/comparison_model.hpp"

#include "api/backend_factory.hpp"
#include "api/feasible_surface.hpp"
#include "common/base/errors.hpp"
#include "common/maps/map_cache.hpp"
#include "common/setup/agent_inputs.hpp"


namespace physarum {
namespace {

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
      if (same_surface_keys(arms[j].scene, a.scene)) a.surface = arms[j].surface;
    std::optional<EvaluatedMaps> maps;
    if (!a.surface) {
      FeasibleSurface feasible = prepare_feasible_surface(a.scene, steps_per_seed(a.scene), cache, a.log);
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

// Fig. 10c: another agent count with the deposit rescaled so that U (Eq. 5) stays the same. (A
// deposit rate given by a map is left as it is: its values are per vertex.)
void keep_U_for_another_agent_count(const Scene& base, nlohmann::json& overrides) {
  const AgentModelSpec& model = base.agent_model();
  if (!overrides.contains("agents") || !overrides["agents"].is_number_integer() || overrides.contains("deposit_rate") ||
      model.parameter_maps[static_cast<size_t>(Param::deposit_rate)])
    return;
  const double agents = overrides["agents"].get<double>();
  if (agents > 0)
    overrides["deposit_rate"] =
        to_file_units(parameter_spec(Param::deposit_rate), model.parameters[Param::deposit_rate]) * model.agents / agents;
}

void describe_agent_arm(const Arm& arm, nlohmann::ordered_json& row) { row["agents"] = arm.scene.agent_model().agents; }

}  // namespace

const ComparisonModel& agent_comparison() {
  static const ComparisonModel model{
      "an agent-model scene",
      [](const std::string& fault) { return fault.rfind("rd-", 0) != 0; },
      nullptr,
      &keep_U_for_another_agent_count,
      &prepare_agent_model_arms,
      &describe_agent_arm,
      nullptr,
  };
  return model;
}

}  // namespace physarum
