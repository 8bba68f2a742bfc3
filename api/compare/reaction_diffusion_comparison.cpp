// Reaction-diffusion's harness (api/compare/comparison_model.hpp): its arms measured by
// common/harness/reaction_diffusion_metrics.hpp, its planted faults (rd-*), and what it refuses: stored
// reference statistics (its seeds are short, both arms run here) and faults that would change nothing.
#include "api/compare/comparison_model.hpp"

#include "api/backend_factory.hpp"
#include "common/base/errors.hpp"
#include "common/harness/reaction_diffusion_metrics.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/setup/reaction_diffusion_build.hpp"


namespace physarum {
namespace {

// Reaction-diffusion arms: the surface (built once where shared) and maps as `physarum run` builds
// them, then per seed the system with that seed's noise and spots. The pattern scale that picks the
// spectral metrics is the continuum system's, taken from the arm judged against, so that two arms
// on different triangulations measure the same metric set.
void prepare_reaction_diffusion_arms(std::vector<Arm>& arms) {
  std::vector<std::shared_ptr<const EvaluatedMaps>> maps(arms.size());
  for (size_t i = 0; i < arms.size(); ++i) {
    Arm& a = arms[i];
    for (size_t j = 0; j < i; ++j)
      if (same_surface_keys(arms[j].scene, a.scene)) a.surface = arms[j].surface;
    if (!a.surface)
      a.surface = std::make_shared<const PreparedSurface>(prepare_scene_surface(a.scene, a.log));
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

void refuse_reaction_diffusion_request(const ComparisonRequest& o, const Scene& scene) {
  if (!o.store_reference.empty() || !o.reference_stats.empty())
    throw UsageError(o.scene + ": stored reference statistics (--store-reference, --reference-stats) are for the agent "
                     "model; a reaction-diffusion scene runs both arms here (its seeds are short)");
  const ReactionDiffusionSpec& system = *scene.reaction_diffusion();
  // rd-no-feed drops the coefficient F from the first formula (opencl/reaction_diffusion.cpp):
  // a model without F (turing, ...) runs unchanged.
  if (o.fault == "rd-no-feed") {
    bool has_feed = false;
    for (const auto& [name, value] : system.coefficients) has_feed = has_feed || name == "F";
    if (!has_feed)
      throw UsageError("--fault rd-no-feed: " + o.scene + "'s model (" + system.model +
                       ") has no feed coefficient F (it would change nothing)");
  }
  // rd-lane-mixup is a fault of the wide vector that only five or more morphogens use.
  if (o.fault == "rd-lane-mixup" && system.morphogens.size() < 5)
    throw UsageError("--fault rd-lane-mixup: " + o.scene + " has " + std::to_string(system.morphogens.size()) +
                     " morphogens; the fault is in the step of five or more (it would change nothing)");
}

void describe_reaction_diffusion_arm(const Arm& arm, nlohmann::ordered_json& row) {
  const ReactionDiffusionSpec& rd = *arm.scene.reaction_diffusion();
  row["model"] = rd.model;
  row["integrator"] = integrator_name(rd.integrator);
  row["preview_morphogen"] = rd.preview_morphogen;
}

// The run length is the scene's, not the agent model's compare defaults, so the report says it.
void describe_reaction_diffusion_run(const Arm& first, nlohmann::ordered_json& report) {
  const ComparisonSettings& c = first.scene.comparison;
  report["run_length"] = {{"burn_in", c.burn_in}, {"duration", c.duration}, {"sample_interval", c.sample_interval}};
}

}  // namespace

const ComparisonModel& reaction_diffusion_comparison() {
  static const ComparisonModel model{
      "a reaction-diffusion scene",
      [](const std::string& fault) { return fault.rfind("rd-", 0) == 0; },
      &refuse_reaction_diffusion_request,
      nullptr,
      &prepare_reaction_diffusion_arms,
      &describe_reaction_diffusion_arm,
      &describe_reaction_diffusion_run,
  };
  return model;
}

}  // namespace physarum
