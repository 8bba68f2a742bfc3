#pragma once
// The two triangular solves of a supernodal Cholesky factor P A P' = L L' (CHOLMOD's LL' layout),
// done here rather than by cholmod_solve so that they run on both cores. One right-hand side
// streams the whole factor twice (forward, then backward: ~416 MB at a million faces) for two flops
// per entry, so the solve is bound by memory bandwidth, which one core cannot use up (CHOLMOD's
// serial solve ran at ~6 GB/s of the machine's ~30).
//
// Parallelism is by subtrees of the supernodal elimination tree (proportional mapping): the
// heaviest subtrees are split into their children until the "frontier" subtrees fall into
// kSolveBins bins of nearly equal stored entries. Forward, each bin solves its subtrees leaves
// first; a supernode's updates to rows of its own subtree stay in its bin, those to rows above the
// frontier (the "top": the last separators of the nested dissection, ~12 % of the entries on a
// sphere) go to the bin's private buffer, added in bin order before the top is solved. The top is
// a chain of large dense supernodes, so it is cut into blocks instead (rows forward, columns
// backward), which the threads take in order, each waiting for the blocks it reads. Backward is
// the reverse: the top first, then the bins, each reading only its own and the top's values.
// Bins, blocks and every sum's order depend only on the factor's structure, so the result is the
// same bits whatever the thread count or timing.
#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace physarum {

// The arrays of a supernodal LL' factor, as CHOLMOD keeps them (int indices), borrowed: supernode k
// holds columns super[k] .. super[k+1]-1; its row indices are s[pi[k] .. pi[k+1]) (the first
// ncols being its own columns, all ascending), and its values a dense column-major block of
// nrows x ncols (leading dimension nrows) at x + px[k]. perm[i] is the row of A eliminated i-th.
template <class Scalar>
struct BasicSupernodalFactorView {
  int n = 0, supernodes = 0;
  const int* super = nullptr;
  const int* pi = nullptr;
  const int* px = nullptr;
  const int* s = nullptr;
  const Scalar* x = nullptr;
  const int* perm = nullptr;
};
using SupernodalFactorView = BasicSupernodalFactorView<double>;

// The number of bins the subtrees are split into: fixed (not the machine's thread count) so that the
// summation order, hence the result, is the same everywhere; 4 rather than 2 so that the two cores
// still balance when one of them is busy with something else for a while.
inline constexpr int kSolveBins = 4;

// Below this many stored entries (8 MB of doubles, 16 MB of floats: a sphere of ~25 k faces), the
// solve is serial: two threads' start and the waits between the bins and the top cost as much as
// they save (measured on spot's pheromone system, float: 1.2 M entries 0.78 ms serial and 0.77 ms
// on two cores; 2.8 M entries 1.95 vs 1.35 ms; 5.7 M entries 5.1 vs 3.1 ms). Above it the solve
// streams from memory, which one core cannot saturate. (The threshold was 4 M entries while the
// supernodes were solved by Eigen's general kernels, whose per-supernode cost hid the gain.)
inline constexpr std::size_t kMinParallelSolveEntries = std::size_t{1} << 20;

template <class Scalar>
class BasicSupernodalSolve {
 public:
  // Plans the solve for `factor` (which must outlive this object). Parallel when it stores at
  // least `min_parallel_entries` entries.
  explicit BasicSupernodalSolve(const BasicSupernodalFactorView<Scalar>& factor,
                                std::size_t min_parallel_entries = kMinParallelSolveEntries);

  // x with P' L L' P x = b, i.e. A x = b, for n values each; b and x may be the same array (b is
  // read whole before x is written). Thread-safe.
  void solve(const Scalar* b, Scalar* x) const;
  // The same on vectors (std::invalid_argument when b has another size).
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> solve(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& b) const;

  // The factor it solves with.
  const BasicSupernodalFactorView<Scalar>& factor() const { return f_; }
  // For tests and benchmarks: how the supernodes were split (bins == 0: all serial).
  int bins() const { return static_cast<int>(bin_nodes_.size()); }
  std::size_t entries() const { return entries_; }
  std::size_t top_entries() const { return top_entries_; }
  // The top's work items (one per small supernode, one per block of a large one, forward and backward).
  int top_tasks() const { return static_cast<int>(tasks_.size()); }
  int top_supernodes() const { return static_cast<int>(top_nodes_.size()); }

 private:
  // One piece of the top's work. Forward, a large supernode is cut into blocks of rows, each of
  // which waits for the blocks of columns left of it to be solved; backward into blocks of columns,
  // each waiting for those below it. Tasks are claimed in list order and wait only for earlier
  // ones, so any number of threads finishes them (one does them in order), and each sum runs in
  // the same order whoever computes it.
  struct TopTask {
    enum Kind { kForwardNode, kForwardRows, kBackwardNode, kBackwardColumns } kind;
    int top = 0;               // index into top_nodes_
    int first = 0, last = 0;   // rows (forward) or columns (backward) of the supernode's block
    int flag = 0;              // this block's done flag (large supernodes)
  };

  void forward(int k, Scalar* y, Scalar* top_buffer, Scalar* work) const;
  void backward(int k, Scalar* y, Scalar* work) const;
  void plan_top();
  void run_top(Scalar* y, Scalar* x) const;

  BasicSupernodalFactorView<Scalar> f_;
  int max_rows_ = 0;
  // Per bin, its supernodes in ascending order (children before parents).
  std::vector<std::vector<int>> bin_nodes_;
  // The supernodes outside every bin, ascending.
  std::vector<int> top_nodes_;
  // Per supernode in a bin: how many of its rows below its own columns lie in its bin; the rest
  // (rows are ascending, and top columns come after every column of the subtrees below them) are top rows.
  std::vector<int> private_rows_;
  // top_slot_[column]: its index among the top's columns, or -1.
  std::vector<int> top_slot_;
  std::vector<int> top_columns_;
  std::vector<TopTask> tasks_;
  // Per top supernode: its forward and its backward tasks' count, and its first done flag.
  std::vector<int> forward_tasks_, backward_tasks_, first_flag_;
  int flags_ = 0;
  std::size_t entries_ = 0, top_entries_ = 0;
};

extern template class BasicSupernodalSolve<float>;
extern template class BasicSupernodalSolve<double>;
using SupernodalSolve = BasicSupernodalSolve<double>;

}  // namespace physarum
