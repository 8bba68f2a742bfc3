#include "api/compare/comparison_fields.hpp"

#include "api/compare/comparison_arms.hpp"
#include "common/output/labelled_panels.hpp"
#include "common/surface/full_resolution_mesh.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace physarum {
namespace {

constexpr int kPanelWidth = 480, kPanelHeight = 360;

std::string caption(const Arm& arm, const std::string& what) {
  char faces[64];
  std::snprintf(faces, sizeof faces, " (%d faces)", arm.surface->domain.face_count);
  return arm.label + faces + ": " + what;
}

}  // namespace

void SeedFields::add(int seed_index, const IntrinsicVertexData<double>& field) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (seed_index == 0) first_ = field;
  if (sum_.empty()) sum_.assign(field.size(), 0.0);
  for (size_t i = 0; i < field.size() && i < sum_.size(); ++i) sum_[i] += field[i];
  ++count_;
}

int SeedFields::count() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return count_;
}

IntrinsicVertexData<double> SeedFields::first() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return first_;
}

IntrinsicVertexData<double> SeedFields::mean() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  IntrinsicVertexData<double> m = sum_;
  for (double& x : m) x /= std::max(1, count_);
  return m;
}

bool write_comparison_fields(const std::string& path, const std::vector<Arm>& arms) {
  // One colour scale for every panel: the arms' own levels (Arm::field_levels) where they have them,
  // else the range of their first seeds' fields.
  PreviewOptions options;
  options.width = kPanelWidth;
  options.height = kPanelHeight;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const Arm& arm : arms) {
    if (!arm.fields || arm.fields->count() == 0) continue;
    if (arm.field_levels) {
      low = std::min(low, (*arm.field_levels)[0]), high = std::max(high, (*arm.field_levels)[1]);
      continue;
    }
    for (double x : arm.fields->first()) low = std::min(low, x), high = std::max(high, x);
  }
  if (!(high > low)) return false;
  options.coloring.low = low;
  options.coloring.high = high;
  std::vector<LabelledPanel> panels;
  for (const Arm& arm : arms) {
    if (!arm.fields || arm.fields->count() == 0) continue;
    const FullResolutionMesh full = build_full_resolution_mesh(arm.surface->input, arm.surface->domain);
    const IntrinsicVertexData<double> first = arm.fields->first();
    if (!first.empty())
      panels.push_back({render_preview(full.mesh, full.vertex_values(first), options), caption(arm, "first seed")});
    panels.push_back({render_preview(full.mesh, full.vertex_values(arm.fields->mean()), options),
                      caption(arm, "mean of " + std::to_string(arm.fields->count()) + " seeds")});
  }
  write_rgb_png(path, arrange_panels(panels, 2));
  return true;
}

}  // namespace physarum
