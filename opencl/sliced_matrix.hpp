#pragma once
// A sparse matrix in sliced ELLPACK form with slices of PHYSARUM_SLICE_ROWS (4) consecutive rows,
// the layout of the forward-Euler sub-step on the device. A slice holds as many slots as its
// longest row has entries; slot k stores entry k of each of the slice's rows side by side, so one
// int4/float4 load serves four rows and a work-item runs one loop of uniform length for all four:
// no per-row loop exit to mispredict, and vector arithmetic on CPU devices. Rows with fewer entries
// than the slice's longest are padded with value 0 at their own column (a valid index whose value
// the row reads anyway); rows past the matrix's end, in the last slice, likewise at column rows-1.
// Entries keep their CSR order within a row, so a row's sum is accumulated in the same order.
#include "common/csr_matrix.hpp"

#include <vector>

namespace physarum::opencl {

struct SlicedMatrix {
  int rows = 0;
  std::vector<int> slice_start;  // slices + 1 entries, in slots: slice s is slots [start[s], start[s+1])
  std::vector<int> column;       // PHYSARUM_SLICE_ROWS per slot
  std::vector<float> value;      // PHYSARUM_SLICE_ROWS per slot, rounded from the CSR's doubles
  int slices() const { return static_cast<int>(slice_start.size()) - 1; }
};

SlicedMatrix slice_rows(const CsrMatrix& csr);

}  // namespace physarum::opencl
