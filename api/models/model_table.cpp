// The registration of every model: one entry each (api/models/<model>_model.cpp says what it does),
// chosen by a visit of the scene's model, so a model added to SceneModel does not compile until it
// is registered here.
#include "api/models/model_table.hpp"

#include "api/compare/comparison_model.hpp"
#include "common/base/errors.hpp"
#include "common/base/overloaded.hpp"

namespace physarum {

// The entries, each defined in its model's file.
ModelEntry agent_model_entry();
ModelEntry reaction_diffusion_model_entry();
ModelEntry growth_model_entry();

const ModelEntry& model_entry(const Scene& scene) {
  static const ModelEntry agents = agent_model_entry();
  static const ModelEntry reaction_diffusion = reaction_diffusion_model_entry();
  static const ModelEntry growth = growth_model_entry();
  return std::visit(overloaded{[&](const AgentModelSpec&) -> const ModelEntry& { return agents; },
                               [&](const ReactionDiffusionSpec&) -> const ModelEntry& { return reaction_diffusion; },
                               [&](const GrowthSpec&) -> const ModelEntry& { return growth; }},
                    scene.model);
}

const ComparisonModel& comparison_model_of(const Scene& scene, const std::string& where) {
  const ModelEntry& entry = model_entry(scene);
  if (!entry.comparison) throw InputError(where + ": " + entry.why_not_compared);
  return *entry.comparison;
}

}  // namespace physarum
