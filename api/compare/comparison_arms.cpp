#include "api/compare/comparison_arms.hpp"

#include "api/compare/comparison_model.hpp"
#include "common/base/errors.hpp"
#include "common/scene/scene_overrides.hpp"

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

std::vector<std::string> names(const std::vector<MetricInfo>& metrics) {
  std::vector<std::string> n;
  for (const MetricInfo& info : metrics) n.push_back(info.name);
  return n;
}

}  // namespace

// Steps of one seed (burn-in + duration): the run whose work the fail-fast checks estimate.
long long steps_per_seed(const Scene& scene) {
  return std::max<long long>(1, std::llround((scene.comparison.burn_in + scene.comparison.duration) / scene.time_step));
}

bool same_surface_keys(const Scene& a, const Scene& b) {
  auto key = [](const Scene& s) {
    return std::make_tuple(s.mesh, s.scale_to_area.value_or(-1.0), s.max_circumradius.value_or(-1.0), s.min_angle_deg);
  };
  return key(a) == key(b);
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
  // The model's harness, or a one-line refusal before anything is built.
  const ComparisonModel& model = comparison_model_of(base, request.scene_path);
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
      if (model.complete_arm_overrides) model.complete_arm_overrides(base, overrides);
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
    arms[i].log = request.log;
    if (request.keep_fields) arms[i].fields = std::make_shared<SeedFields>();
  }

  model.prepare_arms(arms);
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
