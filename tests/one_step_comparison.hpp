#pragma once
// The deterministic layer of the OpenCL-against-reference comparison, shared by the tests and the
// device check: one step from identical states. What may differ afterwards is float32 against
// double: positions and headings agree to ~1e-6 unless a sensor comparison is a near-tie or a trace
// passes within float rounding of a vertex; callers bound the number of disagreeing agents.
#include "common/setup/agent_inputs.hpp"
#include "opencl/agent_simulation.hpp"
#include "reference/agent_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace physarum::testing {

using opencl::ComputeContext;
using opencl::OpenCLAgentSimulation;
using opencl::OpenCLBackendOptions;
struct StepComparison {
  int agents = 0;
  int mismatched = 0;
  double worst_position = 0.0;
  double field_error = 0.0;  // max |u_ocl - u_ref| / max |u_ref|
  std::string first_mismatch;
  bool canaries_damaged = false;
};

// Develops a pattern with the reference for `warmup` steps (so clocks, ages and the field are those
// of a running simulation), hands the device's float copy of that state to BOTH backends and takes
// one step on each.
inline StepComparison compare_one_step(const ComputeContext& compute, const SurfaceDomain& domain,
                                       const Scene& scene, int warmup, const OpenCLBackendOptions& options = {}) {
  ReferenceAgentSimulation developed(domain, constant_parameters(scene, domain), simulation_settings(scene));
  developed.run(warmup);

  OpenCLAgentSimulation device(compute, domain, constant_parameters(scene, domain), simulation_settings(scene), options);
  device.write_agents(developed.agents());
  device.set_field(developed.field());
  const Agents start = device.read_agents();  // float-rounded: the common starting point
  const IntrinsicVertexData<double> field = device.field_values();

  ReferenceAgentSimulation reference(domain, constant_parameters(scene, domain), simulation_settings(scene));
  reference.agents() = start;
  reference.set_field(field);

  reference.step();
  device.step();
  const Agents a = reference.agents();
  const Agents b = device.read_agents();

  StepComparison c;
  c.agents = a.count();
  for (int i = 0; i < a.count(); ++i) {
    const double dp = (a.position[i] - b.position[i]).norm();
    const double dh = (a.heading[i] - b.heading[i]).norm();
    const double dclock = std::abs(a.time_since_decision[i] - b.time_since_decision[i]) +
                          std::abs(a.accumulated_turn[i] - b.accumulated_turn[i]);
    const double dage = std::abs(a.age[i] - b.age[i]) + std::abs(a.exposure[i] - b.exposure[i]) +
                        std::abs(a.exposure_threshold[i] - b.exposure_threshold[i]);
    const bool same = a.face[i] == b.face[i] && dp <= 1e-5 && dh <= 1e-5 && dclock <= 1e-5 && dage <= 1e-5;
    if (!same) {
      ++c.mismatched;
      if (c.first_mismatch.empty())
        c.first_mismatch = "agent " + std::to_string(i) + ": face " + std::to_string(a.face[i]) + " vs " +
                           std::to_string(b.face[i]) + ", |dp| " + std::to_string(dp) + ", |dh| " +
                           std::to_string(dh) + ", clock " + std::to_string(dclock) + ", age " + std::to_string(dage);
    } else {
      c.worst_position = std::max(c.worst_position, dp);
    }
  }
  const IntrinsicVertexData<double> ur = reference.field(), uo = device.field_values();
  double scale = 0.0, err = 0.0;
  for (size_t i = 0; i < ur.size(); ++i) {
    scale = std::max(scale, std::abs(ur[i]));
    err = std::max(err, std::abs(ur[i] - uo[i]));
  }
  c.field_error = err / scale;
  c.canaries_damaged = !device.damaged_canaries().empty();
  return c;
}

}  // namespace physarum::testing
