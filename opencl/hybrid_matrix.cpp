#include "opencl/hybrid_matrix.hpp"

#include "kernels/device_types.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace physarum::opencl {

HybridMatrix to_hybrid(const CsrMatrix& csr, int stride) {
  constexpr int W = PHYSARUM_ELL_WIDTH;
  if (stride < csr.rows || csr.rows <= 0)
    throw std::invalid_argument("hybrid matrix: stride " + std::to_string(stride) + " for " +
                                std::to_string(csr.rows) + " rows");
  HybridMatrix h;
  h.rows = csr.rows;
  h.stride = stride;
  const size_t slots = static_cast<size_t>(W) * static_cast<size_t>(stride);
  h.column.resize(slots);
  h.value.assign(slots, 0.0f);
  h.overflow_start.push_back(0);
  for (int row = 0; row < stride; ++row) {
    const int begin = row < csr.rows ? csr.row_start[row] : 0;
    const int length = row < csr.rows ? csr.row_start[row + 1] - begin : 0;
    for (int k = 0; k < W; ++k) {
      const size_t at = static_cast<size_t>(k) * static_cast<size_t>(stride) + static_cast<size_t>(row);
      h.column[at] = k < length ? csr.column[begin + k] : std::min(row, csr.rows - 1);
      if (k < length) h.value[at] = static_cast<float>(csr.value[begin + k]);
    }
    if (length <= W) continue;
    h.overflow_row.push_back(row);
    for (int k = W; k < length; ++k) {
      h.overflow_column.push_back(csr.column[begin + k]);
      h.overflow_value.push_back(static_cast<float>(csr.value[begin + k]));
    }
    h.overflow_start.push_back(static_cast<int>(h.overflow_column.size()));
  }
  return h;
}

}  // namespace physarum::opencl
