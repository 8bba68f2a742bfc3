#include "opencl/runtime/compute_context.hpp"

#include "opencl/runtime/opencl_error.hpp"

namespace physarum::opencl {

ComputeContext make_compute_context(const std::string& device_spec) {
  ComputeContext c;
  c.device = select_device(device_spec);
  try {
    c.context = cl::Context(c.device.device);
    c.queue = cl::CommandQueue(c.context, c.device.device);
  } catch (const cl::Error& e) {
    throw device_error("creating a context on " + c.device.device_name + " (" + e.what() + ")", e.err());
  }
  return c;
}

}  // namespace physarum::opencl
