#pragma once
// The field layers of a reference backend (agents and reaction-diffusion alike): the dynamic layers
// first (the pheromone of each species, or the morphogens), which the model advances, then the
// static ones (fixed maps added later). The layer calls of SimulationBackend, with their checks
// (common/simulation/simulation_backend.hpp), live here once; the OpenCL backends keep their
// layers in device buffers instead (opencl/field.hpp).
#include "common/base/element_data.hpp"

#include <string>
#include <vector>

namespace physarum {

class FieldLayers {
 public:
  // `who` starts every InputError ("simulation", "reaction-diffusion").
  FieldLayers(std::vector<IntrinsicVertexData<double>> dynamic, int vertex_count, std::string who);

  int size() const { return static_cast<int>(layers_.size()); }
  IntrinsicVertexData<double>& operator[](size_t layer) { return layers_[layer]; }
  const IntrinsicVertexData<double>& operator[](size_t layer) const { return layers_[layer]; }
  IntrinsicVertexData<double>& at(int layer) { return layers_.at(static_cast<size_t>(layer)); }
  const IntrinsicVertexData<double>& at(int layer) const { return layers_.at(static_cast<size_t>(layer)); }
  const std::vector<IntrinsicVertexData<double>>& all() const { return layers_; }

  // The layer, after check_layer_index (`what`: the backend call, for the message).
  const IntrinsicVertexData<double>& checked(int layer, const char* what) const;
  // add_static_layer, set_field, fill_field with their checks.
  int add_static(const IntrinsicVertexData<double>& values);
  void set(const IntrinsicVertexData<double>& values, int layer);
  void fill(double value, int layer);
  // restore_state's copy, element by element into the buffers as sized (no allocation), after
  // check_state_fits has accepted `saved`.
  void copy_from(const std::vector<IntrinsicVertexData<double>>& saved);

 private:
  std::vector<IntrinsicVertexData<double>> layers_;
  int vertex_count_ = 0;
  std::string who_;
};

}  // namespace physarum
