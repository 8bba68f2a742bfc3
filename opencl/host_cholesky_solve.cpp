#include "opencl/host_cholesky_solve.hpp"

#include "common/base/errors.hpp"
#include "common/numerics/shared_cholesky.hpp"
#include "common/numerics/supernodal_solve.hpp"
#include "opencl/runtime/device_tuning.hpp"
#include "opencl/runtime/flush_denormals.hpp"

#include <Eigen/SparseCholesky>

#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace physarum::opencl {

namespace {

using DoubleLdlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

// One entry of L's strict lower triangle as a sweep reads it: the other index (its column, in a
// row; its row, in a column) beside its value, one stream instead of two. Packed to 4 bytes so a
// double entry takes 12 bytes, as Eigen's separate arrays do, not 16: past the cache the sweeps
// are bound by these bytes (x86 and ARMv8 load misaligned doubles in hardware).
#pragma pack(push, 4)
template <class Scalar>
struct TriangleEntry {
  int index;
  Scalar value;
};
#pragma pack(pop)
static_assert(sizeof(TriangleEntry<float>) == 8 && sizeof(TriangleEntry<double>) == 12,
              "triangle entries: an int beside a float or a double, no padding");

// L's strict lower triangle by lines (rows, or columns): line i is entries[start[i] .. start[i+1]).
template <class Scalar>
struct TriangleLines {
  std::vector<int> start;
  std::vector<TriangleEntry<Scalar>> entries;
};

// The sum of value * y[index] over `count` entries, in four independent partial sums: a surface
// factor's lines hold ~10-30 entries, and one chain of dependent additions would wait for the
// adder's latency at every entry.
template <class Scalar>
inline Scalar line_dot(const TriangleEntry<Scalar>* e, int count, const Scalar* y) {
  Scalar s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  int k = 0;
  for (; k + 4 <= count; k += 4) {
    s0 += e[k].value * y[e[k].index];
    s1 += e[k + 1].value * y[e[k + 1].index];
    s2 += e[k + 2].value * y[e[k + 2].index];
    s3 += e[k + 3].value * y[e[k + 3].index];
  }
  for (; k < count; ++k) s0 += e[k].value * y[e[k].index];
  return (s0 + s1) + (s2 + s3);
}

// P S P^T = L D L^T at one precision, solved by two sweeps: forward along L's rows (dot products) or
// down its columns (each column's value subtracted from the rows below), backward along its
// columns (the rows of L^T: dot products).
template <class Scalar>
struct LdltSweeps {
  std::vector<int> permutation;  // row i of S is row permutation[i] of the factor
  TriangleLines<Scalar> rows;  // empty when L is kept by columns only
  TriangleLines<Scalar> columns;
  std::vector<Scalar> inverse_pivot;  // 1 / D
  std::vector<Scalar> work;           // P b, then the solution in the factor's order

  // From Eigen's factor, with L's rows copied when both copies take at most max_row_copy_bytes;
  // false when a pivot is not positive (or its inverse not finite) at Scalar.
  bool assign(const DoubleLdlt& ldlt, int n, std::size_t max_row_copy_bytes) {
    const Eigen::VectorXi& p = ldlt.permutationP().indices();  // empty: no permutation
    permutation.resize(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) permutation[static_cast<size_t>(i)] = p.size() == n ? p[i] : i;
    const Eigen::SparseMatrix<double>& L = ldlt.matrixL().nestedExpression();  // unit diagonal not read
    columns.start.assign(static_cast<size_t>(n) + 1, 0);
    rows.start.assign(static_cast<size_t>(n) + 1, 0);
    columns.entries.clear();
    columns.entries.reserve(static_cast<size_t>(L.nonZeros()));
    for (int j = 0; j < n; ++j) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
        if (it.row() > j) {
          columns.entries.push_back({static_cast<int>(it.row()), static_cast<Scalar>(it.value())});
          ++rows.start[static_cast<size_t>(it.row()) + 1];
        }
      columns.start[static_cast<size_t>(j) + 1] = static_cast<int>(columns.entries.size());
    }
    if (2 * columns.entries.size() * sizeof(TriangleEntry<Scalar>) <= max_row_copy_bytes) {
      for (int i = 0; i < n; ++i) rows.start[static_cast<size_t>(i) + 1] += rows.start[static_cast<size_t>(i)];
      // Columns in ascending order leave every row's entries in ascending column order.
      rows.entries.resize(columns.entries.size());
      std::vector<int> next(rows.start.begin(), rows.start.end() - 1);
      for (int j = 0; j < n; ++j)
        for (int k = columns.start[static_cast<size_t>(j)]; k < columns.start[static_cast<size_t>(j) + 1]; ++k) {
          const TriangleEntry<Scalar>& e = columns.entries[static_cast<size_t>(k)];
          rows.entries[static_cast<size_t>(next[static_cast<size_t>(e.index)]++)] = {j, e.value};
        }
    } else {
      rows = {};
    }
    const Eigen::VectorXd& D = ldlt.vectorD();
    inverse_pivot.resize(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      const Scalar pivot = static_cast<Scalar>(D[i]);
      if (!(D[i] > 0.0) || !(pivot > Scalar(0)) || !std::isfinite(Scalar(1) / pivot)) return false;
      inverse_pivot[static_cast<size_t>(i)] = Scalar(1) / pivot;
    }
    work.assign(static_cast<size_t>(n), Scalar(0));
    return true;
  }

  void solve(const float* b, float* x) {
    const int n = static_cast<int>(work.size());
    Scalar* y = work.data();
    for (int i = 0; i < n; ++i) y[permutation[static_cast<size_t>(i)]] = static_cast<Scalar>(b[i]);
    // L z = P b, from the first row (L's diagonal is 1).
    const TriangleEntry<Scalar>* by_column = columns.entries.data();
    if (!rows.start.empty()) {
      const TriangleEntry<Scalar>* by_row = rows.entries.data();
      for (int i = 0; i < n; ++i) {
        const int first = rows.start[static_cast<size_t>(i)];
        y[i] -= line_dot(by_row + first, rows.start[static_cast<size_t>(i) + 1] - first, y);
      }
    } else {
      for (int j = 0; j < n; ++j) {
        const Scalar z = y[j];
        const TriangleEntry<Scalar>* e = by_column + columns.start[static_cast<size_t>(j)];
        const int count = columns.start[static_cast<size_t>(j) + 1] - columns.start[static_cast<size_t>(j)];
        for (int k = 0; k < count; ++k) y[e[k].index] -= e[k].value * z;
      }
    }
    // L^T w = D^-1 z, from the last row of L^T (column of L).
    for (int j = n - 1; j >= 0; --j) {
      const int first = columns.start[static_cast<size_t>(j)];
      y[j] = y[j] * inverse_pivot[static_cast<size_t>(j)] -
             line_dot(by_column + first, columns.start[static_cast<size_t>(j) + 1] - first, y);
    }
    for (int i = 0; i < n; ++i) x[i] = static_cast<float>(y[permutation[static_cast<size_t>(i)]]);
  }
};

// P S P^T = L L^T in CHOLMOD's supernodal layout (METIS nested dissection), kept at Scalar and solved
// by common/numerics/supernodal_solve.hpp: dense column blocks that carry one row index per block row, not one
// per entry (half the bytes of an (index, value) pair in float), and the elimination tree's subtrees
// on both cores once the factor is past the cache.
template <class Scalar>
struct SupernodalSweeps {
  std::vector<int> super, pi, px, rows, permutation;
  std::vector<Scalar> values;
  std::unique_ptr<BasicSupernodalSolve<Scalar>> plan;
  std::vector<Scalar> work;  // b and x at Scalar, when that is not float

  // False when a diagonal entry of L is not positive and finite at Scalar.
  bool assign(const SupernodalFactorView& f) {
    auto copy = [](const int* data, int count) { return std::vector<int>(data, data + count); };
    super = copy(f.super, f.supernodes + 1);
    pi = copy(f.pi, f.supernodes + 1);
    px = copy(f.px, f.supernodes + 1);
    rows = copy(f.s, f.pi[f.supernodes]);
    permutation = copy(f.perm, f.n);
    values.resize(static_cast<size_t>(f.px[f.supernodes]));
    for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<Scalar>(f.x[i]);
    for (int k = 0; k < f.supernodes; ++k) {
      const int height = pi[static_cast<size_t>(k) + 1] - pi[static_cast<size_t>(k)];
      for (int c = 0; c < super[static_cast<size_t>(k) + 1] - super[static_cast<size_t>(k)]; ++c) {
        const Scalar diagonal = values[static_cast<size_t>(px[static_cast<size_t>(k)] + c * height + c)];
        if (!(diagonal > Scalar(0)) || !std::isfinite(Scalar(1) / diagonal)) return false;
      }
    }
    BasicSupernodalFactorView<Scalar> view;
    view.n = f.n;
    view.supernodes = f.supernodes;
    view.super = super.data();
    view.pi = pi.data();
    view.px = px.data();
    view.s = rows.data();
    view.x = values.data();
    view.perm = permutation.data();
    // The parallel threshold is one of bytes (the cache's size), counted here in doubles.
    plan = std::make_unique<BasicSupernodalSolve<Scalar>>(view, kMinParallelSolveEntries * sizeof(double) / sizeof(Scalar));
    if constexpr (!std::is_same_v<Scalar, float>) work.resize(static_cast<size_t>(f.n));
    return true;
  }

  void solve(const float* b, float* x) {
    if constexpr (std::is_same_v<Scalar, float>) {
      plan->solve(b, x);
    } else {
      for (size_t i = 0; i < work.size(); ++i) work[i] = static_cast<Scalar>(b[i]);
      plan->solve(work.data(), work.data());
      for (size_t i = 0; i < work.size(); ++i) x[i] = static_cast<float>(work[i]);
    }
  }
};

}  // namespace

struct HostCholeskySolve::Factor {
  FactorPrecision precision;
  bool supernodal = false;
  LdltSweeps<float> single;
  LdltSweeps<double> twice;
  SupernodalSweeps<float> single_supernodal;
  SupernodalSweeps<double> twice_supernodal;
};

HostCholeskySolve::~HostCholeskySolve() = default;

HostCholeskySolve::HostCholeskySolve(const CsrMatrix& system, FactorPrecision precision, const std::string& what,
                                     std::size_t max_row_copy_bytes, int min_supernodal_rows)
    : n_(system.rows), factor_(std::make_unique<Factor>()) {
  Factor& f = *factor_;
  f.precision = precision;
  if (n_ >= min_supernodal_rows) {
    f.supernodal = true;
    bool factored = false;
    std::string cholmod_error;
    try {
      const Eigen::SparseMatrix<double> S = system.to_eigen();
      SharedCholesky cholesky(S);
      const int index = cholesky.factor(S, what.c_str());
      const SupernodalFactorView& view = cholesky.supernodal_solve(index).factor();
      factored = precision == FactorPrecision::Single ? f.single_supernodal.assign(view)
                                                      : f.twice_supernodal.assign(view);
    } catch (const std::runtime_error& e) {  // a pivot <= 0 in double, or CHOLMOD's analysis failed
      cholmod_error = std::string(": ") + e.what();
    }
    if (!factored)
      throw InputError(what + ": the implicit system could not be factorised on the host (not positive definite in " +
                       (precision == FactorPrecision::Single ? "float" : "double") + ")" + cholmod_error);
    return;
  }
  // S is symmetric, so its CSR rows are its CSC columns. LDL^T factors an indefinite matrix too:
  // positive definite means every pivot > 0.
  const DoubleLdlt ldlt(system.to_eigen());
  bool factored = ldlt.info() == Eigen::Success;
  if (factored)
    factored = precision == FactorPrecision::Single ? f.single.assign(ldlt, n_, max_row_copy_bytes)
                                                    : f.twice.assign(ldlt, n_, max_row_copy_bytes);
  if (!factored)
    throw InputError(what + ": the implicit system could not be factorised on the host (not positive definite in " +
                     (precision == FactorPrecision::Single ? "float" : "double") + ")");
}

void HostCholeskySolve::solve(const float* b, float* x) {
  // Decayed fields' tails (opencl/runtime/flush_denormals.hpp). The supernodal solve's helper threads start
  // from this one and inherit its floating-point environment (POSIX threads; Linux copies it).
  const FlushDenormalsToZero flush;
  Factor& f = *factor_;
  if (f.supernodal) {
    if (f.precision == FactorPrecision::Single) f.single_supernodal.solve(b, x);
    else f.twice_supernodal.solve(b, x);
  } else {
    if (f.precision == FactorPrecision::Single) f.single.solve(b, x);
    else f.twice.solve(b, x);
  }
}

bool implicit_solve_on_host(const DeviceInfo& device, int vertex_count) {
  return vertex_count <= tuning_for(device).host_implicit_solve_max_vertices;
}

}  // namespace physarum::opencl
