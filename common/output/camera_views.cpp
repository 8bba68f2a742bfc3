#include "common/output/camera_views.hpp"

#include "common/base/errors.hpp"

#include <cstdio>

namespace physarum {

CameraView preview_view() { return {"three_quarter", 35.0, 25.0}; }

std::vector<CameraView> standard_views(int n) {
  if (n < 1 || n > 360) throw UsageError("--views " + std::to_string(n) + " must be between 1 and 360");
  if (n == 1) return {preview_view()};
  // 89 degrees, not 90: at the pole "up" (the y axis) is parallel to the view direction.
  if (n == 3) return {{"front", 0.0, 0.0}, {"side", 90.0, 0.0}, {"top", 0.0, 89.0}};
  std::vector<CameraView> views;
  for (int k = 0; k < n; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "turntable_%03d", k);
    views.push_back({name, preview_view().azimuth_deg + 360.0 * k / n, preview_view().elevation_deg});
  }
  return views;
}

}  // namespace physarum
