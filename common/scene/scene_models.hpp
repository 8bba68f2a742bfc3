#pragma once
// The models a scene can run, registered once: each is one alternative of SceneModel. A model's
// scene part lives in its own files (scene_agents, scene_reaction_diffusion, scene_growth) and gives,
// under the names below, what the scene layer does with every model alike:
//
//   std::optional<Spec> read_model(ModelTag<Spec>, const nlohmann::json& scene, const std::string& source)
//       its keys read from the scene object, or nullopt when the scene is not of this model (tried
//       from the last alternative to the first; the first, the agent model, is the default and
//       always answers);
//   std::string model_key(const Spec&)                    the scene's "model" value, for messages;
//   bool compares_over_its_run_length(const Spec&)        compare's default burn-in and duration are
//       halves of the scene's run (a reaction's time scale) rather than the agent model's seconds;
//   void validate_model(const Spec&, const MapSet&, const std::string& source)   its checks;
//   nlohmann::ordered_json model_json(const Spec&, const Scene&)   its whole description (what a
//       checkpoint's identity and run.json record).
//
// The api side of a model (its backend, run, harness) is its entry in api/models/model_table.cpp;
// docs/library.md ("A new model") has the recipe.
#include "common/scene/scene_agents.hpp"
#include "common/scene/scene_growth.hpp"
#include "common/scene/scene_reaction_diffusion.hpp"

#include <variant>

namespace physarum {

using SceneModel = std::variant<AgentModelSpec, ReactionDiffusionSpec, GrowthSpec>;

}  // namespace physarum
