#include "opencl/field.hpp"

#include "common/base/errors.hpp"
#include "opencl/runtime/opencl_error.hpp"

namespace physarum::opencl {

DeviceVertexData<double> read_field_values(const ComputeContext& compute, const DeviceBuffer& values, int vertex_count,
                                           const std::string& name) {
  std::vector<float> u(static_cast<size_t>(vertex_count));
  try {
    compute.queue.enqueueReadBuffer(values.buffer, CL_TRUE, 0, values.payload_bytes, u.data());
  } catch (const cl::Error& e) {
    throw device_error("reading the " + name + " back from " + compute.device.device_name, e.err());
  }
  return DeviceVertexData<double>(std::vector<double>(u.begin(), u.end()));
}

void write_field_values(const ComputeContext& compute, const DeviceBuffer& values, const DeviceVertexData<double>& u,
                        int vertex_count, const std::string& name) {
  if (u.size() != static_cast<size_t>(vertex_count))
    throw InputError("opencl " + name + ": set_concentration got " + std::to_string(u.size()) + " values for " +
                     std::to_string(vertex_count) + " vertices");
  const std::vector<float> f(u.begin(), u.end());
  try {
    compute.queue.enqueueWriteBuffer(values.buffer, CL_TRUE, 0, values.payload_bytes, f.data());
  } catch (const cl::Error& e) {
    throw device_error("writing the " + name + " to " + compute.device.device_name, e.err());
  }
}

}  // namespace physarum::opencl
