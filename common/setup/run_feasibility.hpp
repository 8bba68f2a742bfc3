#pragma once
// Fail fast on inputs that cannot work: checks that run before anything big is allocated or long
// is computed, and that either refuse (InputError: what was asked, what it would take, what to
// change) or return warnings for the command line. Every check reads plain Scene fields in this one
// place (scene.time_step, scene.decay_rate, ...), so a change of how parameters are stored touches
// this file only.
//   1. the refinement's size, from the area and the circumradius bound, before refining
//      (common/intrinsic/refinement_estimate.hpp, where the triangulation is built);
//   2. the time step against the model's own time scales (decay, turn decisions, sensor crossing);
//   3. the work of a run (sub-steps, face crossings, lengths against the surface's size);
//   4. host and device memory against what the agents and the surface need.
#include "common/base/number_format.hpp"
#include "common/intrinsic/refinement_estimate.hpp"
#include "common/scene/scene.hpp"
#include "common/surface/surface_domain.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace physarum {

// ---- 2. time scales ----
// Above this decay_rate * time_step the field forgets everything within a step (e^-20 ~ 2e-9 of it
// survives): the pattern cannot build up and the result means nothing.
constexpr double kMaxDecayPerStep = 20.0;

// Warnings (one line each) for a time step longer than a time scale of the model; InputError
// listing every refusal where the result cannot mean anything: more turn decisions per step than
// the model takes (`max_turn_decisions_per_step`, the reference's kMaxTurnDecisionsPerStep), a
// decay_rate * time_step above kMaxDecayPerStep.
std::vector<std::string> check_time_scales(const Scene& scene, int max_turn_decisions_per_step);

// ---- 3. work of a run ----
struct WorkEstimate {
  int vertices = 0, faces = 0;
  double mean_edge = 0.0;                 // m, of an equilateral face of the mean face area
  double diameter = 0.0;                  // m, bounding-box diagonal of the scaled surface
  double sub_steps_per_step = 1.0;        // forward Euler's, from the stability limit (1: backward)
  double crossings_per_agent_step = 0.0;  // movement + sensors, from their lengths / mean_edge
  long long steps = 0;
  double operations = 0.0;  // agent-steps x (1 + crossings) + steps x sub-steps x Laplacian entries
  std::string describe() const;  // one line for stderr
};
// More explicit sub-steps than this per step: the diffusion alone sweeps the mesh 10^5 times a step.
constexpr double kMaxSubStepsPerStep = 1e5;
// More elementary operations than this (~1e8..1e9 a second on one core): days of work.
constexpr double kMaxOperations = 1e14;

WorkEstimate estimate_work(const Scene& scene, const SurfaceDomain& domain, double diameter, long long steps,
                           int max_turn_decisions_per_step);
// InputError (with the numbers and what to change) when a length exceeds the surface's diameter or
// the estimate passes kMaxSubStepsPerStep or kMaxOperations.
void check_work(const Scene& scene, const WorkEstimate& work);

// ---- 4. memory ----
struct MemoryNeed {
  double host_bytes = 0.0;
  double device_bytes = 0.0;             // 0: no device
  double largest_device_buffer = 0.0;    // bytes of the largest single device allocation
  std::string breakdown;                 // how the numbers were reached, for the message
};
// MemAvailable from /proc/meminfo, else sysconf's available pages.
double available_host_memory_bytes();
// InputError when the need exceeds the available host memory, the device's global memory or its
// largest allocation (device_global_bytes 0: no device to check).
// `source` names the scene in the message.
void check_memory(const std::string& source, const MemoryNeed& need, double host_available_bytes,
                  const std::string& device_name = "", double device_global_bytes = 0.0,
                  double device_max_allocation_bytes = 0.0);

}  // namespace physarum
