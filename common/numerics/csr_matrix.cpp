#include "common/numerics/csr_matrix.hpp"

#include <cassert>

namespace physarum {

CsrMatrix CsrMatrix::from_eigen(const Eigen::SparseMatrix<double, Eigen::RowMajor>& m) {
  // Copy through the row iterators rather than the raw buffers: the Eigen matrix may be
  // uncompressed (inner non-zeros with gaps), and the copy must not carry those gaps.
  CsrMatrix out;
  out.rows = static_cast<int>(m.rows());
  out.cols = static_cast<int>(m.cols());
  out.row_start.assign(out.rows + 1, 0);
  out.column.reserve(static_cast<size_t>(m.nonZeros()));
  out.value.reserve(static_cast<size_t>(m.nonZeros()));
  for (int r = 0; r < out.rows; ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(m, r); it; ++it) {
      out.column.push_back(static_cast<int>(it.col()));
      out.value.push_back(it.value());
    }
    out.row_start[r + 1] = static_cast<int>(out.column.size());
  }
  return out;
}

Eigen::SparseMatrix<double, Eigen::RowMajor> CsrMatrix::to_eigen() const {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(value.size());
  for (int r = 0; r < rows; ++r)
    for (int k = row_start[r]; k < row_start[r + 1]; ++k) triplets.emplace_back(r, column[k], value[k]);
  Eigen::SparseMatrix<double, Eigen::RowMajor> m(rows, cols);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

void CsrMatrix::multiply(const std::vector<double>& x, std::vector<double>& y) const {
  assert(static_cast<int>(x.size()) == cols);
  y.assign(static_cast<size_t>(rows), 0.0);
  for (int r = 0; r < rows; ++r) {
    double sum = 0.0;
    for (int k = row_start[r]; k < row_start[r + 1]; ++k) sum += value[k] * x[column[k]];
    y[r] = sum;
  }
}

}  // namespace physarum
