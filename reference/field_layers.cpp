#include "reference/field_layers.hpp"

#include "common/simulation/simulation_backend.hpp"

#include <algorithm>
#include <utility>

namespace physarum {

FieldLayers::FieldLayers(std::vector<IntrinsicVertexData<double>> dynamic, int vertex_count, std::string who)
    : layers_(std::move(dynamic)), vertex_count_(vertex_count), who_(std::move(who)) {}

const IntrinsicVertexData<double>& FieldLayers::checked(int layer, const char* what) const {
  check_layer_index(layer, size(), who_, what);
  return layers_[static_cast<size_t>(layer)];
}

int FieldLayers::add_static(const IntrinsicVertexData<double>& values) {
  const int layer = size();
  check_layer_values(values, vertex_count_, layer, who_, "add_static_layer");
  layers_.push_back(values);
  return layer;
}

void FieldLayers::set(const IntrinsicVertexData<double>& values, int layer) {
  checked(layer, "set_field");
  check_layer_values(values, vertex_count_, layer, who_, "set_field");
  layers_[static_cast<size_t>(layer)] = values;
}

void FieldLayers::fill(double value, int layer) {
  checked(layer, "fill_field");
  check_layer_value(value, layer, who_, "fill_field");
  IntrinsicVertexData<double>& f = layers_[static_cast<size_t>(layer)];
  f.assign(f.size(), value);
}

void FieldLayers::copy_from(const std::vector<IntrinsicVertexData<double>>& saved) {
  for (size_t layer = 0; layer < layers_.size(); ++layer)
    std::copy(saved[layer].begin(), saved[layer].end(), layers_[layer].begin());
}

}  // namespace physarum
