#include "common/setup/run_feasibility.hpp"

#include "common/base/errors.hpp"
#include "common/model/diffusion_decay.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace physarum {
namespace {

// Joins reasons into one message: "cannot run SOURCE: reason; reason".
[[noreturn]] void refuse(const std::string& source, const std::vector<std::string>& reasons) {
  std::string m = "refusing " + (source.empty() ? std::string("the scene") : source) + ": ";
  for (size_t i = 0; i < reasons.size(); ++i) m += (i ? "; " : "") + reasons[i];
  throw InputError(m);
}

}  // namespace

// ---- 2. time scales ----

std::vector<std::string> check_time_scales(const Scene& scene, int max_turn_decisions_per_step) {
  const ParameterValues& p = scene.agent_model().parameters;
  std::vector<std::string> warnings, refusals;
  const double dt = scene.time_step;
  // Turn decisions: the model takes at most max_turn_decisions_per_step of them in one step and
  // drops the rest, so a longer step silently changes the model.
  const double decisions = p[Param::turn_frequency] * dt;
  if (decisions > max_turn_decisions_per_step)
    refusals.push_back("time_step " + format_number(dt) + " s holds " + format_number(decisions) +
                       " turn decisions (turn_frequency " + format_number(p[Param::turn_frequency]) +
                       " /s), more than the " + std::to_string(max_turn_decisions_per_step) +
                       " per step the model takes; use a time_step of at most " +
                       format_number(max_turn_decisions_per_step / p[Param::turn_frequency]) + " s");
  else if (decisions > 1.0)
    warnings.push_back("time_step " + format_number(dt) + " s is longer than the turn-decision period 1/turn_frequency = " +
                       format_number(1.0 / p[Param::turn_frequency]) + " s: " + format_number(decisions) +
                       " decisions per step read the same sensors");
  // Decay: past kMaxDecayPerStep the field forgets within one step.
  const double decay = p[Param::decay_rate] * dt;
  if (decay > kMaxDecayPerStep)
    refusals.push_back("decay_rate * time_step = " + format_number(p[Param::decay_rate]) + " /s * " + format_number(dt) +
                       " s = " + format_number(decay) + " (above " + format_number(kMaxDecayPerStep) +
                       "): the pheromone decays to e^-" + format_number(decay) +
                       " within one step, so the field means nothing; use a time_step of at most " +
                       format_number(1.0 / p[Param::decay_rate]) + " s (the decay time 1/decay_rate)");
  else if (decay > 1.0)
    warnings.push_back("time_step " + format_number(dt) + " s is longer than the decay time 1/decay_rate = " +
                       format_number(1.0 / p[Param::decay_rate]) + " s: the field keeps e^-" + format_number(decay) +
                       " of itself from one step to the next");
  // Sensors: an agent that moves farther than its sensor distance in one step steps past what it sensed.
  if (p[Param::move_rate] > 0.0 && p[Param::sensor_distance] > 0.0 && p[Param::move_rate] * dt > p[Param::sensor_distance])
    warnings.push_back("time_step " + format_number(dt) +
                       " s is longer than the time to cross a sensor distance, sensor_distance / move_rate = " +
                       format_number(p[Param::sensor_distance] / p[Param::move_rate]) + " s: agents move past what they sensed");
  if (!refusals.empty()) refuse(scene.source, refusals);
  return warnings;
}

// ---- 3. work of a run ----

std::string WorkEstimate::describe() const {
  char b[400];
  std::snprintf(b, sizeof b,
                "physarum: estimate: %d vertices, %d faces (mean edge %g m, diameter %g m); %g diffusion sub-steps "
                "per step; ~%.3g face crossings per agent-step; %lld steps, ~%.3g operations",
                vertices, faces, mean_edge, diameter, sub_steps_per_step, crossings_per_agent_step, steps, operations);
  return b;
}

WorkEstimate estimate_work(const Scene& scene, const SurfaceDomain& domain, double diameter, long long steps,
                           int max_turn_decisions_per_step) {
  const AgentModelSpec& model = scene.agent_model();
  const ParameterValues& p = model.parameters;
  WorkEstimate w;
  w.vertices = domain.vertex_count;
  w.faces = domain.face_count;
  w.diameter = diameter;
  w.steps = steps;
  const double face_area = domain.face_count > 0 ? domain.total_area / domain.face_count : 0.0;
  w.mean_edge = std::sqrt(4.0 / std::sqrt(3.0) * face_area);
  if (model.integrator == Integrator::Forward && domain.vertex_count > 0) {
    const size_t n = static_cast<size_t>(domain.vertex_count);
    IntrinsicVertexData<double> diffuse_over_mass(n), decay(n, p[Param::decay_rate]);
    for (size_t i = 0; i < n; ++i) diffuse_over_mass[i] = p[Param::diffuse_rate] / domain.vertex_mass[i];
    const double stable = forward_euler_stable_step(domain.laplacian, diffuse_over_mass, decay);
    w.sub_steps_per_step = std::isfinite(stable) && scene.time_step > stable ? std::ceil(scene.time_step / stable) : 1.0;
  }
  const double decisions = std::min<double>(p[Param::turn_frequency] * scene.time_step, max_turn_decisions_per_step);
  const double path = p[Param::move_rate] * scene.time_step + 3.0 * p[Param::sensor_distance] * std::max(decisions, 0.0);
  w.crossings_per_agent_step = w.mean_edge > 0.0 ? path / w.mean_edge : 0.0;
  const double laplacian_entries = static_cast<double>(domain.laplacian.value.size());
  w.operations = static_cast<double>(steps) * (static_cast<double>(model.agents) * (1.0 + w.crossings_per_agent_step) +
                                               w.sub_steps_per_step * laplacian_entries);
  return w;
}

void check_work(const Scene& scene, const WorkEstimate& w) {
  const ParameterValues& p = scene.agent_model().parameters;
  std::vector<std::string> reasons;
  const std::string diameter = "the surface's diameter (bounding-box diagonal " + format_number(w.diameter) + " m)";
  if (p[Param::sensor_distance] > w.diameter)
    reasons.push_back("sensor_distance " + format_number(p[Param::sensor_distance]) + " m exceeds " + diameter +
                      ": sensors wrap the surface; use a smaller sensor_distance or a larger scale_to_area");
  if (p[Param::move_rate] * scene.time_step > w.diameter)
    reasons.push_back("move_rate * time_step = " + format_number(p[Param::move_rate] * scene.time_step) +
                      " m per step exceeds " + diameter +
                      ": agents wrap the surface every step; use a smaller time_step or move_rate, or a larger "
                      "scale_to_area");
  if (w.sub_steps_per_step > kMaxSubStepsPerStep)
    reasons.push_back("forward Euler needs " + format_number(w.sub_steps_per_step) +
                      " diffusion sub-steps per step (stability limit of diffuse_rate " +
                      format_number(p[Param::diffuse_rate]) + " m^2/s and decay_rate " + format_number(p[Param::decay_rate]) +
                      " /s on edges of " + format_number(w.mean_edge) + " m), above " +
                      format_number(kMaxSubStepsPerStep) +
                      "; use \"integrator\": \"backward\", a smaller time_step or diffuse_rate, or a coarser mesh");
  if (w.operations > kMaxOperations)
    reasons.push_back("the run needs about " + format_number(w.operations) + " operations (above " +
                      format_number(kMaxOperations) +
                      ", days at 1e8..1e9 a second); use fewer agents, steps or sub-steps");
  if (!reasons.empty()) refuse(scene.source, reasons);
}

// ---- 4. memory ----

double available_host_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream in(line.substr(13));
    double kib = 0.0;
    if (in >> kib) return kib * 1024.0;
  }
  const long pages = ::sysconf(_SC_AVPHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page)
                               : std::numeric_limits<double>::infinity();
}

void check_memory(const std::string& source, const MemoryNeed& need, double host_available_bytes,
                  const std::string& device_name, double device_global_bytes, double device_max_allocation_bytes) {
  std::vector<std::string> reasons;
  if (need.host_bytes > host_available_bytes)
    reasons.push_back("needs about " + format_bytes(need.host_bytes) + " of host memory, " +
                      format_bytes(host_available_bytes) + " available");
  if (device_global_bytes > 0.0 && need.device_bytes > device_global_bytes)
    reasons.push_back("needs about " + format_bytes(need.device_bytes) + " of device memory, " + device_name +
                      " has " + format_bytes(device_global_bytes));
  if (device_max_allocation_bytes > 0.0 && need.largest_device_buffer > device_max_allocation_bytes)
    reasons.push_back("its largest device buffer would be " + format_bytes(need.largest_device_buffer) + ", " +
                      device_name + " allocates at most " + format_bytes(device_max_allocation_bytes));
  if (!reasons.empty()) {
    reasons.back() += " (" + need.breakdown + "); use fewer agents or a coarser mesh";
    refuse(source, reasons);
  }
}

}  // namespace physarum
