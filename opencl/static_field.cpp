#include "opencl/static_field.hpp"

#include "common/base/errors.hpp"
#include "opencl/runtime/opencl_error.hpp"

namespace physarum::opencl {

OpenCLStaticField::~OpenCLStaticField() = default;

OpenCLStaticField::OpenCLStaticField(const ComputeContext& compute, const std::string& name,
                                     const DeviceVertexData<double>& vertex_mass,
                                     const DeviceVertexData<double>& values)
    : compute_(compute), name_(name), vertex_count_(static_cast<int>(vertex_mass.size())) {
  if (vertex_mass.empty())
    throw InputError("opencl " + name_ + ": the domain has no vertices");
  if (values.size() != vertex_mass.size())
    throw InputError("opencl " + name_ + ": got " + std::to_string(values.size()) + " values for " +
                     std::to_string(vertex_mass.size()) + " vertices");
  std::vector<float> mass(vertex_mass.size());
  for (size_t i = 0; i < mass.size(); ++i) {
    if (!(vertex_mass[i] > 0.0))
      throw InputError("opencl " + name_ + ": vertex " + std::to_string(i) + " (device order) has lumped mass " +
                       std::to_string(vertex_mass[i]) + " (must be > 0)");
    mass[i] = static_cast<float>(vertex_mass[i]);
  }
  mass_ = upload_buffer(compute, name_ + " vertex mass", mass, CL_MEM_READ_ONLY, false);
  u_ = allocate_written<cl_float>(compute, name_ + " values", vertex_mass.size());
  set_concentration(values);
  statistics_ = std::make_unique<DeviceFieldStatistics>(compute, mass_.buffer, vertex_count_);
}

DeviceVertexData<double> OpenCLStaticField::concentration() const {
  return read_field_values(compute_, u_, vertex_count_, name_);
}

void OpenCLStaticField::set_concentration(const DeviceVertexData<double>& u) {
  write_field_values(compute_, u_, u, vertex_count_, name_);
}

void OpenCLStaticField::fill(double value) {
  try {
    compute_.queue.enqueueFillBuffer(u_.buffer, static_cast<float>(value), 0, u_.payload_bytes);
  } catch (const cl::Error& e) {
    throw device_error("filling the " + name_ + " on " + compute_.device.device_name, e.err());
  }
}

FieldStatistics OpenCLStaticField::statistics(double U) const { return statistics_->compute(u_.buffer, U); }

double OpenCLStaticField::total_amount() const { return statistics_->weighted_sum(u_.buffer); }

std::vector<std::string> OpenCLStaticField::damaged_canaries() const {
  std::vector<std::string> damaged = statistics_->damaged_canaries();
  if (!canary_intact(compute_, u_)) damaged.push_back(u_.name);
  return damaged;
}

}  // namespace physarum::opencl
