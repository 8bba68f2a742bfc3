#include "common/model/vertex_parameters.hpp"

#include <algorithm>

namespace physarum {

VertexParameters VertexParameters::constant(const ParameterValues& values, int vertex_count) {
  const auto n = static_cast<std::size_t>(std::max(vertex_count, 0));
  VertexParameters p;
  for (const ParameterSpec& spec : kParameterTable) p[spec.id].assign(n, values[spec.id]);
  return p;
}

bool is_uniform(const IntrinsicVertexData<double>& values) {
  return std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
}

}  // namespace physarum
