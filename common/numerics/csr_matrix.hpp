#pragma once
// Compressed-sparse-row matrix in plain arrays, the form both backends (and device buffers) use.
#include <Eigen/SparseCore>
#include <vector>

namespace physarum {

struct CsrMatrix {
  int rows = 0;
  int cols = 0;
  std::vector<int> row_start;  // rows + 1 entries
  std::vector<int> column;
  std::vector<double> value;

  static CsrMatrix from_eigen(const Eigen::SparseMatrix<double, Eigen::RowMajor>& m);
  Eigen::SparseMatrix<double, Eigen::RowMajor> to_eigen() const;
  // y = A x
  void multiply(const std::vector<double>& x, std::vector<double>& y) const;
};

}  // namespace physarum
