#pragma once
// Building OpenCL programs once per device and keeping the binaries on disk, keyed by a hash of
// everything that can change the result: platform, device, driver version, build options and source
// (the Random123 headers the kernels include count as source).
#include "opencl/runtime/device_selection.hpp"
#include "opencl/runtime/opencl_api.hpp"

#include <string>

namespace physarum::opencl {

// The folder binaries are cached in: $PHYSARUM_CACHE_DIR, else $XDG_CACHE_HOME/physarum, else
// $HOME/.cache/physarum; "" disables caching (also PHYSARUM_CACHE_DIR=off).
std::string program_cache_dir();

// Options every program is built with: OpenCL C 1.2 and the Random123 include path.
std::string base_build_options();

// Builds `source` (label names it in messages, e.g. "agent_step.cl") for one device with
// base_build_options() + extra_options, from the disk cache when possible. A build failure throws
// DeviceError carrying the compiler's log.
cl::Program build_program(const cl::Context& context, const DeviceInfo& device, const std::string& label,
                          const std::string& source, const std::string& extra_options = "");

}  // namespace physarum::opencl
