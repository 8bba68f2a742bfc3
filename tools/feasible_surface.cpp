#include "tools/feasible_surface.hpp"

#include "common/run_feasibility.hpp"
#include "common/agent_model.hpp"

#include <iostream>
#include <string>
#include <unistd.h>

namespace physarum::cli {

SceneSurface prepare_feasible_surface(const Scene& scene, long long steps) {
  for (const std::string& w : check_time_scales(scene, kMaxTurnDecisionsPerStep))
    std::cerr << "physarum: warning: " << w << "\n";
  SceneSurface surface = prepare_scene_surface(scene, [](const std::string& line) { std::cerr << line << "\n"; });
  for (const std::string& w : surface.warnings) std::cerr << "physarum: warning: " << w << "\n";
  const WorkEstimate work = estimate_work(scene, surface.domain, surface.diameter, steps, kMaxTurnDecisionsPerStep);
  // The estimate is for a person waiting: shown on a terminal, and for a run long enough to wait for
  // (about ten seconds of work or more) wherever stderr goes.
  if (::isatty(STDERR_FILENO) == 1 || work.operations > kLongRunOperations) std::cerr << work.describe() << "\n";
  check_work(scene, work);
  return surface;
}

}  // namespace physarum::cli
