#pragma once
// A per-vertex field on the OpenCL device: one float per intrinsic vertex in the device's vertex
// order (opencl/face_records.hpp), with its statistics reduced on the device. What every layer of the
// OpenCL simulation offers, dynamic (opencl/field_model.hpp: advanced each step) or static
// (opencl/static_field.hpp: a fixed map). The counterpart of one entry of the reference simulation's
// layer list (reference/agent_simulation.hpp).
#include "common/base/element_data.hpp"
#include "common/simulation/field_statistics.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/runtime/opencl_api.hpp"

#include <string>
#include <vector>

namespace physarum::opencl {

class OpenCLField {
 public:
  virtual ~OpenCLField() = default;

  // ---- the values, in the device's vertex order ----
  virtual DeviceVertexData<double> concentration() const = 0;  // blocking read-back
  virtual void set_concentration(const DeviceVertexData<double>& u) = 0;
  virtual void fill(double value) = 0;
  // The buffer of values (float per vertex), the same for the field's lifetime: kernels bind it.
  virtual const cl::Buffer& concentration_buffer() const = 0;
  virtual FieldStatistics statistics(double U) const = 0;  // reduced on the device
  virtual double total_amount() const = 0;                 // sum_i m_i u_i

  // Names of the device buffers whose canary region a kernel overwrote (empty when none).
  virtual std::vector<std::string> damaged_canaries() const = 0;
};

// The blocking transfers every field's values take (`name` says which field in messages): a read
// back of `vertex_count` floats as doubles, and a write of doubles as floats, with the count checked.
DeviceVertexData<double> read_field_values(const ComputeContext& compute, const DeviceBuffer& values, int vertex_count,
                                           const std::string& name);
void write_field_values(const ComputeContext& compute, const DeviceBuffer& values, const DeviceVertexData<double>& u,
                        int vertex_count, const std::string& name);

}  // namespace physarum::opencl
