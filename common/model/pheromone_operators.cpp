#include "common/model/pheromone_operators.hpp"

#include <algorithm>

namespace physarum {
namespace {

// A CSR matrix assembled row by row.
struct CsrBuilder {
  CsrMatrix m;
  explicit CsrBuilder(int n) {
    m.rows = m.cols = n;
    m.row_start.push_back(0);
  }
  void add(int col, double v) {
    m.column.push_back(col);
    m.value.push_back(v);
  }
  void end_row() { m.row_start.push_back(static_cast<int>(m.column.size())); }
  bool row_has(int col) const {
    return std::any_of(m.column.begin() + m.row_start.back(), m.column.end(), [col](int c) { return c == col; });
  }
};

}  // namespace

CsrMatrix forward_substep_matrix(const CsrMatrix& L, const IntrinsicVertexData<double>& diffuse_over_mass,
                                 const IntrinsicVertexData<double>& decay_rate, double h) {
  CsrBuilder F(L.rows);
  for (int i = 0; i < L.rows; ++i) {
    const double keep = 1.0 - h * decay_rate[i];
    bool diagonal = false;
    for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
      const int j = L.column[k];
      F.add(j, -h * diffuse_over_mass[i] * L.value[k] + (j == i ? keep : 0.0));
      diagonal |= j == i;
    }
    if (!diagonal) F.add(i, keep);  // a Laplacian row without a diagonal entry
    F.end_row();
  }
  return F.m;
}

BackwardEulerSystem backward_euler_system(const CsrMatrix& L, const IntrinsicVertexData<double>& mass,
                                          const IntrinsicVertexData<double>& diffuse_rate,
                                          const IntrinsicVertexData<double>& decay_rate, double dt) {
  const int n = L.rows;
  const size_t un = static_cast<size_t>(n);
  std::vector<char> active(un);
  bool any_active = false;
  for (size_t i = 0; i < un; ++i) any_active |= (active[i] = diffuse_rate[i] > 0.0);
  CsrBuilder S(n), B(n);
  BackwardEulerSystem out;
  out.diagonal_only = !any_active;
  out.inverse_diagonal.assign(un, 1.0);
  for (int i = 0; i < n; ++i) {
    const double m = mass[i];
    const double keep = 1.0 + dt * decay_rate[i];
    if (!active[i]) {
      S.add(i, 1.0);
      B.add(i, 1.0 / keep);
    } else {
      const double r = diffuse_rate[i];
      double diagonal = m * keep / r;
      for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
        const int j = L.column[k];
        if (j == i) diagonal += dt * L.value[k];
      }
      for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
        const int j = L.column[k];
        if (j == i) S.add(i, diagonal);
        else if (active[j]) S.add(j, dt * L.value[k]);
      }
      if (!S.row_has(i)) S.add(i, diagonal);  // a Laplacian row without a stored diagonal entry
      out.inverse_diagonal[i] = 1.0 / diagonal;
      B.add(i, m / r);
      for (int k = L.row_start[i]; k < L.row_start[i + 1]; ++k) {
        const int j = L.column[k];
        if (j != i && !active[j]) B.add(j, -dt * L.value[k] / (1.0 + dt * decay_rate[j]));
      }
    }
    S.end_row();
    B.end_row();
  }
  out.system = std::move(S.m);
  out.rhs = std::move(B.m);
  return out;
}

}  // namespace physarum
