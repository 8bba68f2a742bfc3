#include "api/compare/pattern_checks.hpp"

#include "common/harness/common_sampling.hpp"

#include <cstdio>

namespace physarum {

std::vector<UnrepresentedScale> unrepresented_scales(const std::vector<Arm>& arms) {
  std::vector<UnrepresentedScale> out;
  if (arms.size() != 2 || arms[0].surface == arms[1].surface) return out;
  const double edge0 = mean_edge_length(arms[0].surface->domain), edge1 = mean_edge_length(arms[1].surface->domain);
  const int coarser = edge0 > edge1 ? 0 : 1;
  const double h = std::max(edge0, edge1);
  const std::vector<MetricInfo>& metrics = arms[0].metrics;
  for (size_t j = 0; j < metrics.size(); ++j) {
    if (!metrics[j].on_common_sampling || metrics[j].scale >= kRepresentableScaleInEdges * h) continue;
    out.push_back({j, coarser, h, 0.0, false, ""});
  }
  return out;
}

bool judge_unrepresented(std::vector<UnrepresentedScale>& scales, const std::vector<Arm>& arms,
                         const std::vector<std::vector<double>>& arm0, const std::vector<std::vector<double>>& arm1) {
  bool any = false;
  for (UnrepresentedScale& u : scales) {
    const std::vector<std::vector<double>>& finer = u.coarser_arm == 0 ? arm1 : arm0;
    if (finer.empty()) continue;
    double sum = 0.0;
    for (const auto& row : finer) sum += row[u.metric];
    u.finer_power = sum / static_cast<double>(finer.size());
    u.decides = u.finer_power >= kPatternPowerFloor;
    const MetricInfo& m = arms[0].metrics[u.metric];
    char text[512];
    std::snprintf(text, sizeof text,
                  "%s: arm '%s' (mean edge %.3g m) cannot represent its scale %.3g m (fewer than %g edges per "
                  "wavelength); arm '%s' has %.3g there (mean over %zu seeds), %s the %g that makes it a pattern",
                  m.name.c_str(), arms[static_cast<size_t>(u.coarser_arm)].label.c_str(), u.coarser_edge, m.scale,
                  kRepresentableScaleInEdges, arms[static_cast<size_t>(1 - u.coarser_arm)].label.c_str(), u.finer_power,
                  finer.size(), u.decides ? "above" : "below", kPatternPowerFloor);
    u.reason = text;
    any = any || u.decides;
  }
  return any;
}

bool examines_pattern(const std::vector<MetricInfo>& metrics) {
  for (const MetricInfo& m : metrics)
    if (m.pattern_scale() && !m.difference_only) return true;
  return false;
}

std::vector<bool> difference_only_mask(const std::vector<MetricInfo>& metrics) {
  std::vector<bool> mask;
  for (const MetricInfo& m : metrics) mask.push_back(m.difference_only);
  return mask;
}

}  // namespace physarum
