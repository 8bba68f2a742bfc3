// Sliced ELLPACK (opencl/sliced_matrix.hpp) against the CSR matrix it came from: every entry lands
// in its row's lane in CSR order, slices are as long as their longest row, padding is inert, and a
// product computed through the slices equals the CSR product.
#include "kernels/device_types.h"
#include "opencl/sliced_matrix.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace physarum::opencl {
namespace {

// Rows of 0..9 entries (an empty row included) over 23 rows: not a multiple of the slice height.
CsrMatrix random_csr(unsigned seed) {
  std::mt19937 rng(seed);
  CsrMatrix m;
  m.rows = m.cols = 23;
  m.row_start.push_back(0);
  for (int i = 0; i < m.rows; ++i) {
    const int length = i == 5 ? 0 : static_cast<int>(rng() % 10);
    for (int k = 0; k < length; ++k) {
      m.column.push_back(static_cast<int>(rng() % m.cols));
      m.value.push_back(std::uniform_real_distribution<double>(-1.0, 1.0)(rng));
    }
    m.row_start.push_back(static_cast<int>(m.column.size()));
  }
  return m;
}

// y = A x read the way pheromone_forward_substep reads it: slot by slot, all lanes of a slice.
std::vector<float> sliced_product(const SlicedMatrix& s, const std::vector<float>& x) {
  constexpr int R = PHYSARUM_SLICE_ROWS;
  std::vector<float> y(static_cast<size_t>(s.slices()) * R, 0.0f);
  for (int slice = 0; slice < s.slices(); ++slice)
    for (int k = s.slice_start[slice]; k < s.slice_start[slice + 1]; ++k)
      for (int r = 0; r < R; ++r) y[slice * R + r] += s.value[k * R + r] * x[s.column[k * R + r]];
  y.resize(static_cast<size_t>(s.rows));
  return y;
}

TEST(SlicedMatrix, HoldsEveryEntryInItsRowsLaneInOrder) {
  constexpr int R = PHYSARUM_SLICE_ROWS;
  const CsrMatrix csr = random_csr(4);
  const SlicedMatrix s = slice_rows(csr);
  ASSERT_EQ(s.slices(), (csr.rows + R - 1) / R);
  ASSERT_EQ(s.column.size(), static_cast<size_t>(s.slice_start.back()) * R);
  ASSERT_EQ(s.value.size(), s.column.size());
  for (int row = 0; row < s.slices() * R; ++row) {
    const int slice = row / R, lane = row % R;
    const int length = row < csr.rows ? csr.row_start[row + 1] - csr.row_start[row] : 0;
    int longest = 0;
    for (int r = slice * R; r < std::min(slice * R + R, csr.rows); ++r)
      longest = std::max(longest, csr.row_start[r + 1] - csr.row_start[r]);
    ASSERT_EQ(s.slice_start[slice + 1] - s.slice_start[slice], longest) << "slice " << slice;
    for (int k = 0; k < longest; ++k) {
      const size_t at = static_cast<size_t>(s.slice_start[slice] + k) * R + lane;
      if (k < length) {
        EXPECT_EQ(s.column[at], csr.column[csr.row_start[row] + k]) << "row " << row << " entry " << k;
        EXPECT_EQ(s.value[at], static_cast<float>(csr.value[csr.row_start[row] + k])) << "row " << row;
      } else {
        EXPECT_EQ(s.value[at], 0.0f) << "padding of row " << row;
        EXPECT_GE(s.column[at], 0);
        EXPECT_LT(s.column[at], csr.cols) << "padding of row " << row << " must stay a valid index";
      }
    }
  }
}

TEST(SlicedMatrix, ProductEqualsCsrProduct) {
  const CsrMatrix csr = random_csr(9);
  std::mt19937 rng(2);
  std::vector<double> x(static_cast<size_t>(csr.cols));
  for (double& v : x) v = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
  std::vector<double> expected;
  csr.multiply(x, expected);
  const std::vector<float> y = sliced_product(slice_rows(csr), std::vector<float>(x.begin(), x.end()));
  ASSERT_EQ(y.size(), expected.size());
  for (size_t i = 0; i < y.size(); ++i) EXPECT_NEAR(y[i], expected[i], 1e-5) << "row " << i;
  EXPECT_EQ(y[5], 0.0f) << "an empty row";
}

}  // namespace
}  // namespace physarum::opencl
