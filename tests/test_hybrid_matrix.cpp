// Hybrid ELL + CSR (opencl/hybrid_matrix.hpp) against the CSR matrix it came from: every entry lands
// in its row's ELL slot or, past the ELL width, in the row's overflow part, both in CSR order; padding
// is inert and stays a valid index; and a product computed the way the two kernels compute it equals
// the CSR product.
#include "kernels/device_types.h"
#include "opencl/hybrid_matrix.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace physarum::opencl {
namespace {

constexpr int W = PHYSARUM_ELL_WIDTH;

// 23 rows of 0..W+4 entries: an empty row, rows shorter than, exactly as long as and longer than
// the ELL width.
CsrMatrix random_csr(unsigned seed) {
  std::mt19937 rng(seed);
  CsrMatrix m;
  m.rows = m.cols = 23;
  m.row_start.push_back(0);
  for (int i = 0; i < m.rows; ++i) {
    const int length = i == 5 ? 0 : i == 6 ? W : i == 7 ? W + 4 : static_cast<int>(rng() % (W + 5));
    for (int k = 0; k < length; ++k) {
      m.column.push_back(static_cast<int>(rng() % m.cols));
      m.value.push_back(std::uniform_real_distribution<double>(-1.0, 1.0)(rng));
    }
    m.row_start.push_back(static_cast<int>(m.column.size()));
  }
  return m;
}

// n entries uniform in [-1, 1), the vector a product test multiplies.
std::vector<double> random_vector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<double> x(static_cast<size_t>(n));
  for (double& v : x) v = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
  return x;
}

int row_length(const CsrMatrix& m, int row) { return m.row_start[row + 1] - m.row_start[row]; }

// y = A x read the way pheromone_forward_substep and pheromone_forward_overflow read it: every row
// of the stride through all W slots, then the long rows' remainders added on.
std::vector<float> hybrid_product(const HybridMatrix& h, const std::vector<float>& x) {
  std::vector<float> y(static_cast<size_t>(h.stride), 0.0f);
  for (int i = 0; i < h.stride; ++i)
    for (int k = 0; k < h.width; ++k) y[i] += h.value[k * h.stride + i] * x[h.column[k * h.stride + i]];
  for (int j = 0; j < h.overflow_rows(); ++j) {
    float rest = 0.0f;
    for (int k = h.overflow_start[j]; k < h.overflow_start[j + 1]; ++k) rest += h.overflow_value[k] * x[h.overflow_column[k]];
    y[h.overflow_row[j]] += rest;
  }
  for (int i = h.rows; i < h.stride; ++i) EXPECT_EQ(y[i], 0.0f) << "padding row " << i << " must sum to zero";
  y.resize(static_cast<size_t>(h.rows));
  return y;
}

TEST(HybridMatrix, HoldsEveryEntryInItsRowsSlotOrOverflowInOrder) {
  const CsrMatrix csr = random_csr(4);
  const int stride = 32;  // the launch size: rows padded to a work-group multiple
  const HybridMatrix h = to_hybrid(csr, stride);
  ASSERT_EQ(h.stride, stride);
  ASSERT_EQ(h.column.size(), static_cast<size_t>(W * stride));
  ASSERT_EQ(h.value.size(), h.column.size());
  int expected_overflow = 0;
  for (int row = 0; row < csr.rows; ++row) expected_overflow += row_length(csr, row) > W;
  ASSERT_GE(expected_overflow, 2) << "the test matrix should have long rows";
  ASSERT_EQ(h.overflow_rows(), expected_overflow);
  ASSERT_EQ(h.overflow_start.size(), static_cast<size_t>(expected_overflow + 1));
  int j = 0;  // index into the overflow rows
  for (int row = 0; row < stride; ++row) {
    const int length = row < csr.rows ? row_length(csr, row) : 0;
    for (int k = 0; k < W; ++k) {
      const size_t at = static_cast<size_t>(k * stride + row);
      if (k < length) {
        EXPECT_EQ(h.column[at], csr.column[csr.row_start[row] + k]) << "row " << row << " entry " << k;
        EXPECT_EQ(h.value[at], static_cast<float>(csr.value[csr.row_start[row] + k])) << "row " << row;
      } else {
        EXPECT_EQ(h.value[at], 0.0f) << "padding of row " << row;
        EXPECT_GE(h.column[at], 0);
        EXPECT_LT(h.column[at], csr.cols) << "padding of row " << row << " must stay a valid index";
      }
    }
    if (length <= W) continue;
    ASSERT_LT(j, h.overflow_rows());
    EXPECT_EQ(h.overflow_row[j], row);
    ASSERT_EQ(h.overflow_start[j + 1] - h.overflow_start[j], length - W) << "row " << row;
    for (int k = W; k < length; ++k) {
      const int at = h.overflow_start[j] + k - W;
      EXPECT_EQ(h.overflow_column[at], csr.column[csr.row_start[row] + k]) << "row " << row << " entry " << k;
      EXPECT_EQ(h.overflow_value[at], static_cast<float>(csr.value[csr.row_start[row] + k])) << "row " << row;
    }
    ++j;
  }
}

TEST(HybridMatrix, ProductEqualsCsrProduct) {
  const CsrMatrix csr = random_csr(9);
  const std::vector<double> x = random_vector(csr.cols, 2);
  std::vector<double> expected;
  csr.multiply(x, expected);
  for (const int stride : {csr.rows, 64}) {
    const std::vector<float> y = hybrid_product(to_hybrid(csr, stride), std::vector<float>(x.begin(), x.end()));
    ASSERT_EQ(y.size(), expected.size());
    for (size_t i = 0; i < y.size(); ++i) EXPECT_NEAR(y[i], expected[i], 1e-5) << "stride " << stride << ", row " << i;
    EXPECT_EQ(y[5], 0.0f) << "an empty row";
  }
}

TEST(HybridMatrix, RefusesAStrideShorterThanTheMatrix) {
  EXPECT_THROW(to_hybrid(random_csr(1), 22), std::invalid_argument);
  EXPECT_THROW(to_hybrid(random_csr(1), 23, 0), std::invalid_argument);
}

// Narrower blocks than PHYSARUM_ELL_WIDTH (the reaction-diffusion sub-step picks its own): the same
// product, and exactly the rows longer than the width spill.
TEST(HybridMatrix, AnyWidthGivesTheSameProduct) {
  const CsrMatrix csr = random_csr(9);
  const std::vector<double> x = random_vector(csr.cols, 3);
  std::vector<double> expected;
  csr.multiply(x, expected);
  for (const int width : {1, 3, 6, W + 5}) {
    const HybridMatrix h = to_hybrid(csr, 32, width);
    ASSERT_EQ(h.column.size(), static_cast<size_t>(width * 32));
    int longer = 0;
    for (int i = 0; i < csr.rows; ++i) longer += row_length(csr, i) > width;
    EXPECT_EQ(h.overflow_rows(), longer) << "width " << width;
    const std::vector<float> y = hybrid_product(h, std::vector<float>(x.begin(), x.end()));
    for (size_t i = 0; i < y.size(); ++i) EXPECT_NEAR(y[i], expected[i], 1e-5) << "width " << width << ", row " << i;
  }
}

// A matrix of 100 rows: 90 of 6 entries, 7 of 7, 3 of 9. With 3 % allowed to spill the narrowest
// width is 7 (only the 3 rows of 9 are longer); with none, 9; capped at 8, 8; with 10 %, 6.
TEST(HybridMatrix, EllWidthForHoldsAllButTheAllowedShareOfRows) {
  CsrMatrix m;
  m.rows = m.cols = 100;
  m.row_start.push_back(0);
  for (int i = 0; i < m.rows; ++i) {
    const int length = i < 90 ? 6 : i < 97 ? 7 : 9;
    for (int k = 0; k < length; ++k) {
      m.column.push_back((i + k) % m.cols);
      m.value.push_back(1.0);
    }
    m.row_start.push_back(static_cast<int>(m.column.size()));
  }
  EXPECT_EQ(ell_width_for(m, 16, 0.03), 7);
  EXPECT_EQ(ell_width_for(m, 16, 0.0), 9);
  EXPECT_EQ(ell_width_for(m, 8, 0.0), 8);
  EXPECT_EQ(ell_width_for(m, 16, 0.10), 6);
  EXPECT_THROW(ell_width_for(m, 0, 0.03), std::invalid_argument);
}

}  // namespace
}  // namespace physarum::opencl
