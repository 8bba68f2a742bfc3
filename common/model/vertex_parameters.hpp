#pragma once
// Every model parameter stored per intrinsic vertex (paper Sec. 3.3, "Parameter maps"), so a
// spatially varying map changes only how these arrays are filled, not who reads them. One array per
// row of the parameter table (common/model/model_parameters.hpp), in SI units (angles in radians);
// mean_lifetime is +infinity where there is no turnover.
#include "common/base/element_data.hpp"
#include "common/model/model_parameters.hpp"

#include <array>

namespace physarum {

class VertexParameters {
 public:
  IntrinsicVertexData<double>& operator[](Param p) { return values_[static_cast<std::size_t>(p)]; }
  const IntrinsicVertexData<double>& operator[](Param p) const { return values_[static_cast<std::size_t>(p)]; }

  int vertex_count() const { return static_cast<int>(values_.front().size()); }
  // Every parameter constant, equal to `values`, on `vertex_count` vertices.
  static VertexParameters constant(const ParameterValues& values, int vertex_count);

 private:
  std::array<IntrinsicVertexData<double>, kParamCount> values_;
};

// True when every entry of `values` equals the first (an empty array counts as uniform). Lets a
// consumer pick a cheaper or symmetric path when a map is in fact constant.
bool is_uniform(const IntrinsicVertexData<double>& values);

}  // namespace physarum
