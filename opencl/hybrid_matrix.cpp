#include "opencl/hybrid_matrix.hpp"

#include "kernels/device_types.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace physarum::opencl {

HybridMatrix to_hybrid(const CsrMatrix& csr, int stride, int width) {
  const int W = width;
  if (stride < csr.rows || csr.rows <= 0 || width < 1)
    throw std::invalid_argument("hybrid matrix: stride " + std::to_string(stride) + " and width " +
                                std::to_string(width) + " for " + std::to_string(csr.rows) + " rows");
  HybridMatrix h;
  h.rows = csr.rows;
  h.stride = stride;
  h.width = width;
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

int ell_width_for(const CsrMatrix& csr, int max_width, double spill) {
  if (max_width < 1) throw std::invalid_argument("hybrid matrix: ELL width at most " + std::to_string(max_width));
  // rows_longer[w]: the rows with more than w entries (w < max_width), counted once over the rows.
  std::vector<long long> rows_longer(static_cast<size_t>(max_width), 0);
  for (int row = 0; row < csr.rows; ++row) {
    const int length = csr.row_start[row + 1] - csr.row_start[row];
    for (int w = 0; w < std::min(length, max_width); ++w) ++rows_longer[static_cast<size_t>(w)];
  }
  const double allowed = spill * static_cast<double>(csr.rows);
  for (int w = 1; w < max_width; ++w)
    if (static_cast<double>(rows_longer[static_cast<size_t>(w)]) <= allowed) return w;
  return max_width;
}

}  // namespace physarum::opencl
