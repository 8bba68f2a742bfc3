#pragma once
// How the dynamic field layers of the reference simulation advance one time step. A field model
// owns its operators (built once from the domain and the per-vertex parameters); the layers
// themselves belong to the simulation, so one model advances any number of layers (one per species).
// Where the step's deposits enter (before or after the transport) is the model's choice, so a
// reaction term later is a new model, not an edit of the simulation step.
#include "common/base/element_data.hpp"

namespace physarum {

class ReferenceFieldModel {
 public:
  virtual ~ReferenceFieldModel() = default;
  // Advances `layer` (a concentration per intrinsic vertex) by one time step, with the AMOUNTS
  // deposited into it during the step.
  virtual void advance(IntrinsicVertexData<double>& layer, const IntrinsicVertexData<double>& deposits) = 0;
};

}  // namespace physarum
