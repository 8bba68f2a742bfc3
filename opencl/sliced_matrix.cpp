#include "opencl/sliced_matrix.hpp"

#include "kernels/device_types.h"

#include <algorithm>

namespace physarum::opencl {

SlicedMatrix slice_rows(const CsrMatrix& csr) {
  constexpr int R = PHYSARUM_SLICE_ROWS;
  SlicedMatrix s;
  s.rows = csr.rows;
  s.slice_start.push_back(0);
  for (int first = 0; first < csr.rows; first += R) {
    int slots = 0;
    for (int row = first; row < std::min(first + R, csr.rows); ++row)
      slots = std::max(slots, csr.row_start[row + 1] - csr.row_start[row]);
    for (int k = 0; k < slots; ++k)
      for (int row = first; row < first + R; ++row) {
        const bool real = row < csr.rows && k < csr.row_start[row + 1] - csr.row_start[row];
        s.column.push_back(real ? csr.column[csr.row_start[row] + k] : std::min(row, csr.rows - 1));
        s.value.push_back(real ? static_cast<float>(csr.value[csr.row_start[row] + k]) : 0.0f);
      }
    s.slice_start.push_back(s.slice_start.back() + slots);
  }
  return s;
}

}  // namespace physarum::opencl
