#include "common/numerics/shared_cholesky.hpp"

#include "common/numerics/blas_threads.hpp"

#include <cholmod.h>
#include <omp.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace physarum {
namespace {

// CHOLMOD's view of an Eigen matrix (no copy), symmetric: `stype` -1 reads its lower triangle, +1
// its upper one.
cholmod_sparse view(const Eigen::SparseMatrix<double>& m, int stype) {
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(m.rows());
  s.ncol = static_cast<size_t>(m.cols());
  s.nzmax = static_cast<size_t>(m.nonZeros());
  s.p = const_cast<int*>(m.outerIndexPtr());
  s.i = const_cast<int*>(m.innerIndexPtr());
  s.x = const_cast<double*>(m.valuePtr());
  s.stype = stype;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

// CHOLMOD's supernodal factorization opens OpenMP regions of CHOLMOD_OMP_NUM_THREADS threads, a
// number fixed when the library was built (4 in Debian's). On a machine with fewer cores those
// threads outnumber the cores and spin against each other and OpenBLAS's: on two cores the
// factorization of a 9,241-vertex shell's Hessian took 219 ms with them and 134 ms without
// (bench/README.md, "CHOLMOD's threads"). There, while this guard lives, the calling thread runs
// CHOLMOD's regions alone (max-active-levels 0, an ICV of the calling thread: set around each call,
// restored after it).
class SerialOpenMpWhenOversubscribed {
 public:
  SerialOpenMpWhenOversubscribed() {
    static const bool oversubscribed = std::thread::hardware_concurrency() < CHOLMOD_OMP_NUM_THREADS;
    if (!oversubscribed) return;
    previous_ = omp_get_max_active_levels();
    omp_set_max_active_levels(0);
  }
  ~SerialOpenMpWhenOversubscribed() {
    if (previous_ >= 0) omp_set_max_active_levels(previous_);
  }
  SerialOpenMpWhenOversubscribed(const SerialOpenMpWhenOversubscribed&) = delete;
  SerialOpenMpWhenOversubscribed& operator=(const SerialOpenMpWhenOversubscribed&) = delete;

 private:
  int previous_ = -1;
};

// Factors of fewer flops than this (CHOLMOD's count from the analysis) run on serial BLAS
// (common/numerics/blas_threads.hpp has the measurements on either side).
constexpr double kSerialBlasBelowFlops = 1e10;

}  // namespace

struct SharedCholesky::State {
  mutable cholmod_common common{};
  cholmod_factor* symbolic = nullptr;
  std::vector<cholmod_factor*> numeric;
  // Factors released or refused, kept for the next factor(): CHOLMOD refactors into a numeric factor
  // of the same analysis in place, so the values (5.4 M at a 9,241-vertex shell) are allocated once
  // and not zeroed page by page by the kernel at every Newton iteration.
  std::vector<cholmod_factor*> spare;
  std::vector<std::unique_ptr<SupernodalSolve>> solves;  // one per numeric factor
  std::vector<int> outer, inner;  // the pattern
  std::vector<int> identity;      // the permutation when CHOLMOD keeps none
  std::size_t min_parallel_entries = kMinParallelSolveEntries;
  double flops = 0.0;  // of one numeric factorization (CHOLMOD's count from the analysis)
};

SharedCholesky::SharedCholesky(const Eigen::SparseMatrix<double>& pattern, const std::vector<int>* ordering,
                               std::size_t min_parallel_entries)
    : state_(std::make_unique<State>()) {
  state_->min_parallel_entries = min_parallel_entries;
  if (!pattern.isCompressed()) throw std::invalid_argument("SharedCholesky: the matrix must be compressed");
  if (ordering && static_cast<Eigen::Index>(ordering->size()) != pattern.rows())
    throw std::invalid_argument("SharedCholesky: the ordering has " + std::to_string(ordering->size()) + " entries for " +
                                std::to_string(pattern.rows()) + " rows");
  State& s = *state_;
  cholmod_start(&s.common);
  // Nested dissection (METIS) only: CHOLMOD's default also tries AMD and keeps the better, which at
  // a million faces costs more than the factorization itself (measured: 5.5 s analysis, 3.0 s
  // factorization; METIS alone 4.0 s + 2.2 s, and the same fill; AMD alone 0.8 s + 4.1 s with 60 %
  // more fill, which every solve pays again).
  s.common.nmethods = 1;
  s.common.method[0].ordering = ordering ? CHOLMOD_GIVEN : CHOLMOD_METIS;
  // Always LL' (supernodal): for small matrices CHOLMOD would pick a simplicial LDL', which factors
  // an indefinite matrix without complaint instead of refusing it.
  s.common.supernodal = CHOLMOD_SUPERNODAL;
  // No printing: a matrix that is not positive definite is reported by factor()'s exception, and
  // Newton's method (common/shell/shell_equilibrium.cpp) expects and handles that case.
  s.common.print = 0;
  s.outer.assign(pattern.outerIndexPtr(), pattern.outerIndexPtr() + pattern.outerSize() + 1);
  s.inner.assign(pattern.innerIndexPtr(), pattern.innerIndexPtr() + pattern.nonZeros());
  cholmod_sparse a = view(pattern, -1);
  const SerialOpenMpWhenOversubscribed serial;
  s.symbolic = ordering ? cholmod_analyze_p(&a, const_cast<int*>(ordering->data()), nullptr, 0, &s.common)
                        : cholmod_analyze(&a, &s.common);
  if (!s.symbolic || s.common.status != CHOLMOD_OK) {
    cholmod_finish(&s.common);
    throw std::runtime_error("SharedCholesky: CHOLMOD's analysis failed (status " + std::to_string(s.common.status) + ")");
  }
  s.flops = s.common.fl;
}

SharedCholesky::~SharedCholesky() {
  State& s = *state_;
  for (cholmod_factor*& f : s.numeric) cholmod_free_factor(&f, &s.common);
  for (cholmod_factor*& f : s.spare) cholmod_free_factor(&f, &s.common);
  cholmod_free_factor(&s.symbolic, &s.common);
  cholmod_finish(&s.common);
}

int SharedCholesky::factor(const Eigen::SparseMatrix<double>& matrix, const char* what) {
  State& s = *state_;
  if (!matrix.isCompressed() || matrix.outerSize() + 1 != static_cast<Eigen::Index>(s.outer.size()) ||
      !std::equal(s.outer.begin(), s.outer.end(), matrix.outerIndexPtr()) ||
      matrix.nonZeros() != static_cast<Eigen::Index>(s.inner.size()) ||
      !std::equal(s.inner.begin(), s.inner.end(), matrix.innerIndexPtr()))
    throw std::invalid_argument(std::string("SharedCholesky: ") + what + " does not have the analysed pattern");
  cholmod_factor* f = nullptr;
  if (s.spare.empty()) {
    f = cholmod_copy_factor(s.symbolic, &s.common);
    if (!f) throw std::runtime_error(std::string("SharedCholesky: no memory for the factor of ") + what);
  } else {
    f = s.spare.back();
    s.spare.pop_back();
  }
  // The upper triangle: cholmod_factorize permutes a matrix given by it in one transpose, by the
  // lower one in two (each a copy of the matrix).
  cholmod_sparse a = view(matrix, 1);
  {
    const SerialOpenMpWhenOversubscribed serial;
    const SerialBlasScope serial_blas(s.flops < kSerialBlasBelowFlops);
    cholmod_factorize(&a, f, &s.common);
  }
  if (s.common.status != CHOLMOD_OK || f->minor != f->n) {
    if (s.common.status == CHOLMOD_NOT_POSDEF)
      s.spare.push_back(f);  // still a whole numeric factor of the analysis (its last columns zero)
    else
      cholmod_free_factor(&f, &s.common);
    throw std::runtime_error(std::string("the Cholesky factorization of ") + what + " failed (not positive definite)");
  }
  // common.supernodal forces a supernodal LL' of doubles with int indices: the layout our solve reads.
  if (!f->is_super || !f->is_ll || f->xtype != CHOLMOD_REAL || f->itype != CHOLMOD_INT || f->dtype != CHOLMOD_DOUBLE) {
    cholmod_free_factor(&f, &s.common);
    throw std::runtime_error(std::string("SharedCholesky: CHOLMOD's factor of ") + what + " is not a supernodal LL'");
  }
  if (!f->Perm && s.identity.empty()) {
    s.identity.resize(f->n);
    for (size_t i = 0; i < f->n; ++i) s.identity[i] = static_cast<int>(i);
  }
  SupernodalFactorView view;
  view.n = static_cast<int>(f->n);
  view.supernodes = static_cast<int>(f->nsuper);
  view.super = static_cast<const int*>(f->super);
  view.pi = static_cast<const int*>(f->pi);
  view.px = static_cast<const int*>(f->px);
  view.s = static_cast<const int*>(f->s);
  view.x = static_cast<const double*>(f->x);
  view.perm = f->Perm ? static_cast<const int*>(f->Perm) : s.identity.data();
  s.solves.push_back(std::make_unique<SupernodalSolve>(view, s.min_parallel_entries));
  s.numeric.push_back(f);
  return static_cast<int>(s.numeric.size()) - 1;
}

void SharedCholesky::release_factors() {
  State& s = *state_;
  s.solves.clear();
  s.spare.insert(s.spare.end(), s.numeric.begin(), s.numeric.end());
  s.numeric.clear();
}

Eigen::VectorXd SharedCholesky::solve(int index, const Eigen::VectorXd& b) const {
  return state_->solves[static_cast<size_t>(index)]->solve(b);
}

const SupernodalSolve& SharedCholesky::supernodal_solve(int index) const { return *state_->solves[static_cast<size_t>(index)]; }

Eigen::VectorXd SharedCholesky::cholmod_reference_solve(int index, const Eigen::VectorXd& b) const {
  const State& s = *state_;
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(b.size());
  rhs.ncol = 1;
  rhs.nzmax = static_cast<size_t>(b.size());
  rhs.d = static_cast<size_t>(b.size());
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, s.numeric[static_cast<size_t>(index)], &rhs, &s.common);
  if (!x) throw std::runtime_error("SharedCholesky: CHOLMOD's solve failed");
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x), b.size());
  cholmod_free_dense(&x, &s.common);
  return out;
}

std::vector<int> SharedCholesky::ordering() const {
  const cholmod_factor& f = *state_->symbolic;
  const int* perm = static_cast<const int*>(f.Perm);
  return std::vector<int>(perm, perm + f.n);
}

std::vector<int> restricted_ordering(const std::vector<int>& ordering, const std::vector<int>& new_index) {
  std::vector<int> out;
  for (const int v : ordering)
    if (const int i = new_index[static_cast<size_t>(v)]; i >= 0) out.push_back(i);
  return out;
}

}  // namespace physarum
