#pragma once
// Both reaction-diffusion backends of one built system, as `physarum run` builds them
// (api/backend_factory.hpp), optionally with a planted fault in the OpenCL one, and the largest
// element-wise difference of their fields: what the backend-agreement tests compare.
#include "api/backend_factory.hpp"
#include "opencl/planted_faults.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "reaction_diffusion_scene.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace physarum::testing {

inline const opencl::ComputeContext& rd_compute() {
  static const opencl::ComputeContext c = opencl::make_compute_context("");
  return c;
}

inline std::unique_ptr<SimulationBackend> rd_backend(const LoadedReactionDiffusion& rd, BackendChoice choice,
                                                     const std::string& fault = "") {
  opencl::OpenCLBackendOptions options;
  if (!fault.empty()) options.build_options = opencl::fault_build_option(fault);
  return make_reaction_diffusion_backend(choice, choice == BackendChoice::OpenCL ? &rd_compute() : nullptr,
                                         rd.surface.domain, rd.system, options);
}

inline double largest_difference(const SimulationBackend& a, const SimulationBackend& b) {
  double worst = 0.0;
  for (int m = 0; m < a.dynamic_layer_count(); ++m) {
    const auto x = a.field_values(m), y = b.field_values(m);
    for (size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(x[i] - y[i]));
  }
  return worst;
}

}  // namespace physarum::testing
