#pragma once
// A static field layer on the OpenCL device: a fixed map of one float per intrinsic vertex (in the
// device's vertex order) that never advances and never receives deposits; its values change only
// through set_concentration / fill. The counterpart of a static entry of the reference simulation's
// layer list (reference/agent_simulation.hpp). It keeps its own masses for its statistics, so it needs no
// dynamic layer beside it.
#include "common/base/element_data.hpp"
#include "common/simulation/field_statistics.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/field.hpp"
#include "opencl/field_statistics.hpp"

#include <memory>
#include <string>
#include <vector>

namespace physarum::opencl {

class OpenCLStaticField final : public OpenCLField {
 public:
  // vertex_mass: the lumped masses and values: the initial field, both in device vertex order and
  // of one size. `name` prefixes the names of its buffers (messages, damaged canaries). Throws
  // InputError on a size mismatch, no vertices or a mass that is not > 0, DeviceError when a
  // buffer exceeds the device.
  OpenCLStaticField(const ComputeContext& compute, const std::string& name, const DeviceVertexData<double>& vertex_mass,
                    const DeviceVertexData<double>& values);
  ~OpenCLStaticField() override;
  OpenCLStaticField(const OpenCLStaticField&) = delete;
  OpenCLStaticField& operator=(const OpenCLStaticField&) = delete;

  DeviceVertexData<double> concentration() const override;  // blocking read-back, converted to double
  void set_concentration(const DeviceVertexData<double>& u) override;
  void fill(double value) override;
  const cl::Buffer& concentration_buffer() const override { return u_.buffer; }
  FieldStatistics statistics(double U) const override;
  double total_amount() const override;
  std::vector<std::string> damaged_canaries() const override;
  int vertex_count() const { return vertex_count_; }

 private:
  ComputeContext compute_;
  std::string name_;
  int vertex_count_ = 0;
  DeviceBuffer mass_;  // read-only
  DeviceBuffer u_;     // written by fills and writes: canary-guarded
  std::unique_ptr<DeviceFieldStatistics> statistics_;
};

}  // namespace physarum::opencl
