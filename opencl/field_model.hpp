#pragma once
// A dynamic field layer of the OpenCL simulation and the model that advances it (the counterpart of
// reference/field_model.hpp). Unlike the reference, where the simulation keeps the layers and one
// model advances any of them, a device layer owns its buffer beside its operators: the agent kernels
// bind the buffer once, and a model's launches are built around it. Where the step's deposits enter
// is the model's choice, so the simulation step only asks each layer to advance.
#include "common/element_data.hpp"
#include "common/field_statistics.hpp"
#include "opencl/device_buffer.hpp"

#include <string>
#include <vector>

namespace physarum::opencl {

class OpenCLFieldLayer {
 public:
  virtual ~OpenCLFieldLayer() = default;

  // Enqueues one time step with the deposits the agent step accumulated in `cells` (fixed point of
  // `scale`, kernels/deposit_cells.h), which are cleared.
  virtual void advance(const DeviceBuffer& cells, double scale) = 0;

  // ---- the values, in the device's vertex order ----
  virtual DeviceVertexData<double> concentration() const = 0;  // blocking read-back
  virtual void set_concentration(const DeviceVertexData<double>& u) = 0;
  virtual void fill(double value) = 0;
  // The buffer of values (float per vertex), the same for the layer's lifetime: kernels bind it.
  virtual const cl::Buffer& concentration_buffer() const = 0;
  virtual FieldStatistics statistics(double U) const = 0;  // reduced on the device
  virtual double total_amount() const = 0;                 // sum_i m_i u_i

  // Names of the device buffers whose canary region a kernel overwrote (empty when none).
  virtual std::vector<std::string> damaged_canaries() const = 0;
};

}  // namespace physarum::opencl
