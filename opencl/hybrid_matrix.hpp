#pragma once
// A sparse matrix in hybrid ELL + CSR form ("HYB"), the layout of the forward Euler sub-step on the
// device. The first PHYSARUM_ELL_WIDTH entries of every row go to a fixed-width ELL block stored slot
// by slot: entry k of row i at k * stride + i, so neighbouring work-items read neighbouring words
// and every work-item runs the same fixed, unrolled loop, which lets a CPU device vectorise across
// work-items (gathers) and keeps a GPU's loads coalesced. The few rows with more entries keep the
// rest in a small CSR "overflow" part that a second kernel adds on, one work-item per long row, so
// the result stays deterministic. Rows with fewer entries are padded with value 0 at their own column
// (a valid index whose value the row reads anyway); rows past the matrix's end (up to stride) with
// value 0 at column rows - 1. Entries keep their CSR order within a row.
#include "common/csr_matrix.hpp"

#include <vector>

namespace physarum::opencl {

struct HybridMatrix {
  int rows = 0;
  int stride = 0;              // rows of the ELL block, >= rows (the launch's global size)
  std::vector<int> column;     // PHYSARUM_ELL_WIDTH * stride, slot-major
  std::vector<float> value;    // same layout, rounded from the CSR's doubles
  std::vector<int> overflow_row;     // the rows with more than PHYSARUM_ELL_WIDTH entries, ascending
  std::vector<int> overflow_start;   // overflow_row.size() + 1 offsets into overflow_column/value
  std::vector<int> overflow_column;  // those rows' entries past the first PHYSARUM_ELL_WIDTH
  std::vector<float> overflow_value;
  int overflow_rows() const { return static_cast<int>(overflow_row.size()); }
};

// `stride` >= csr.rows: the ELL block's row count, the global size the kernel runs on.
HybridMatrix to_hybrid(const CsrMatrix& csr, int stride);

}  // namespace physarum::opencl
