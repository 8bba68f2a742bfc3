#pragma once
// A sparse matrix in hybrid ELL + CSR form ("HYB"), the layout of the forward Euler sub-step on the
// device. The first `width` entries of every row (PHYSARUM_ELL_WIDTH unless the caller picks one,
// e.g. by ell_width_for) go to a fixed-width ELL block stored slot
// by slot: entry k of row i at k * stride + i, so neighbouring work-items read neighbouring words
// and every work-item runs the same fixed, unrolled loop, which lets a CPU device vectorise across
// work-items (gathers) and keeps a GPU's loads coalesced. The few rows with more entries keep the
// rest in a small CSR "overflow" part that a second kernel adds on, one work-item per long row, so
// the result stays deterministic. Rows with fewer entries are padded with value 0 at their own column
// (a valid index whose value the row reads anyway); rows past the matrix's end (up to stride) with
// value 0 at column rows - 1. Entries keep their CSR order within a row.
#include "common/numerics/csr_matrix.hpp"
#include "kernels/device_types.h"

#include <vector>

namespace physarum::opencl {

struct HybridMatrix {
  int rows = 0;
  int stride = 0;              // rows of the ELL block, >= rows (the launch's global size)
  int width = 0;               // ELL slots per row
  std::vector<int> column;     // width * stride, slot-major
  std::vector<float> value;    // same layout, rounded from the CSR's doubles
  std::vector<int> overflow_row;     // the rows with more than `width` entries, ascending
  std::vector<int> overflow_start;   // overflow_row.size() + 1 offsets into overflow_column/value
  std::vector<int> overflow_column;  // those rows' entries past the first `width`
  std::vector<float> overflow_value;
  int overflow_rows() const { return static_cast<int>(overflow_row.size()); }
};

// `stride` >= csr.rows: the ELL block's row count, the global size the kernel runs on; width >= 1.
HybridMatrix to_hybrid(const CsrMatrix& csr, int stride, int width = PHYSARUM_ELL_WIDTH);

// The narrowest ELL width, at most max_width, that holds all but at most `spill` (a fraction) of
// the rows whole. Every slot costs every row its column and value and a gather, filled or not, while
// an overflow entry costs only its own row: a few long rows are cheaper in the overflow part than a
// wider block. On the intrinsic Delaunay meshes run, the off-diagonal entries of a row (its degree)
// are 7 or fewer in 96-97 % of rows; a regular grid's are 6.
int ell_width_for(const CsrMatrix& csr, int max_width, double spill);

}  // namespace physarum::opencl
