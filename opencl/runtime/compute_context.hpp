#pragma once
// A chosen device with its context and in-order command queue: what every OpenCL object needs.
#include "opencl/runtime/device_selection.hpp"
#include "opencl/runtime/opencl_api.hpp"

#include <string>

namespace physarum::opencl {

struct ComputeContext {
  DeviceInfo device;
  cl::Context context;
  cl::CommandQueue queue;
};

// Selects the device (select_device's rules) and creates its context and queue.
ComputeContext make_compute_context(const std::string& device_spec);

}  // namespace physarum::opencl
