#pragma once
// A dynamic field layer of the OpenCL simulation and the model that advances it (the counterpart of
// reference/field_model.hpp). Unlike the reference, where the simulation keeps the layers and one
// model advances any of them, a device layer owns its buffer beside its operators: the agent kernels
// bind the buffer once, and a model's launches are built around it. Where the step's deposits enter
// is the model's choice, so the simulation step only asks each layer to advance. The values and
// their statistics are every field's (opencl/field.hpp); a static field has them without advance.
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/field.hpp"

namespace physarum::opencl {

class OpenCLFieldLayer : public OpenCLField {
 public:
  // Enqueues one time step with the deposits the agent step accumulated in `cells` (fixed point of
  // `scale`, kernels/deposit_cells.h), which are cleared.
  virtual void advance(const DeviceBuffer& cells, double scale) = 0;
};

}  // namespace physarum::opencl
