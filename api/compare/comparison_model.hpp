#pragma once
// What `physarum compare` does differently for one model: its planted faults and the requests it
// refuses, how an --arm's overrides follow from the base scene, each arm's metrics and measure, and
// its keys in verdict.json. A model's ModelEntry (api/models/model_table.hpp) points at its
// ComparisonModel, or says why the harness has none.
#include "api/comparison.hpp"
#include "api/compare/comparison_arms.hpp"
#include "common/scene/scene.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace physarum {

struct ComparisonModel {
  // How a refusal names its scenes: "an agent-model scene".
  std::string scenes;
  // True for a --fault of this model (a fault of another model would change nothing).
  bool (*owns_fault)(const std::string& fault) = nullptr;
  // The request's refusals of this model (stored statistics, faults that would change nothing); may be null.
  void (*refuse)(const ComparisonRequest& request, const Scene& scene) = nullptr;
  // An --arm's scene overrides completed from the base scene; may be null.
  void (*complete_arm_overrides)(const Scene& base, nlohmann::json& overrides) = nullptr;
  // Each arm's surface, metrics and measure (Arm::measure).
  void (*prepare_arms)(std::vector<Arm>& arms) = nullptr;
  // The model's keys of an arm in verdict.json's "arms", and of the report itself; may be null.
  void (*describe_arm)(const Arm& arm, nlohmann::ordered_json& row) = nullptr;
  void (*describe_run)(const Arm& first, nlohmann::ordered_json& report) = nullptr;
};

// The harness of the scene's model (its ModelEntry's), or InputError "WHERE: why it has none".
const ComparisonModel& comparison_model_of(const Scene& scene, const std::string& where);

// The agent model's harness (api/compare/agent_comparison.cpp) and reaction-diffusion's
// (api/compare/reaction_diffusion_comparison.cpp).
const ComparisonModel& agent_comparison();
const ComparisonModel& reaction_diffusion_comparison();

}  // namespace physarum
