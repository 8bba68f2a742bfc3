#include "common/numerics/supernodal_solve.hpp"

#include "common/base/parallel_chunks.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>

namespace physarum {
namespace {

template <class Scalar>
using ConstBlock = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>, 0, Eigen::OuterStride<>>;
template <class Scalar>
using Vector = Eigen::Map<Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>;
template <class Scalar>
using ConstVector = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>;

// Splitting stops once the bins are within this of perfect balance, or the top would hold more than
// this share of the entries (its small supernodes run one at a time: a chain, as in a 3D grid's
// or a path's elimination tree, is not worth splitting further), or after this many splits.
constexpr double kBalanceTolerance = 0.02;
constexpr double kMaxTopShare = 0.5;
constexpr int kMaxSplits = 4096;
// A top supernode of at least this many entries is cut into blocks: kBlockColumns wide on the
// diagonal (the triangular solves that must wait for each other), kBlockRows tall below it.
constexpr double kLargeTopEntries = 65536;
constexpr int kBlockColumns = 64;
constexpr int kBlockRows = 256;

// Waits until `value` reaches `target` (set by another thread with release order). Yields after a
// short spin: on a busy machine the thread being waited for may not be running.
void wait_until(const std::atomic<int>& value, int target) {
  for (int spin = 0; value.load(std::memory_order_acquire) < target; ++spin)
    if (spin >= 64) std::this_thread::yield();
}

// Longest-processing-time-first: the subtrees, heaviest first, each to the currently lightest bin
// (ties to the lowest bin, so the result depends only on the weights). Returns each subtree's bin.
std::vector<int> balance(const std::vector<int>& roots, const std::vector<double>& weight, std::vector<double>& load) {
  std::vector<int> order(roots.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return weight[static_cast<size_t>(roots[static_cast<size_t>(a)])] > weight[static_cast<size_t>(roots[static_cast<size_t>(b)])];
  });
  load.assign(kSolveBins, 0.0);
  std::vector<int> bin(roots.size());
  for (const int i : order) {
    const int lightest = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    bin[static_cast<size_t>(i)] = lightest;
    load[static_cast<size_t>(lightest)] += weight[static_cast<size_t>(roots[static_cast<size_t>(i)])];
  }
  return bin;
}

}  // namespace

template <class Scalar>
BasicSupernodalSolve<Scalar>::BasicSupernodalSolve(const BasicSupernodalFactorView<Scalar>& factor,
                                                   std::size_t min_parallel_entries)
    : f_(factor) {
  const int ns = f_.supernodes;
  std::vector<int> column_owner(static_cast<size_t>(f_.n));  // supernode holding each column
  std::vector<double> entries(static_cast<size_t>(ns));
  double total = 0.0;
  bool rows_ascending = true;
  for (int k = 0; k < ns; ++k) {
    const int cols = f_.super[k + 1] - f_.super[k], rows = f_.pi[k + 1] - f_.pi[k];
    max_rows_ = std::max(max_rows_, rows);
    for (int c = f_.super[k]; c < f_.super[k + 1]; ++c) column_owner[static_cast<size_t>(c)] = k;
    entries[static_cast<size_t>(k)] = static_cast<double>(rows) * cols;
    total += entries[static_cast<size_t>(k)];
    for (int p = f_.pi[k] + 1; p < f_.pi[k + 1]; ++p) rows_ascending = rows_ascending && f_.s[p - 1] < f_.s[p];
  }
  // The parent of a supernode holds its first row below its own columns; parents come after children.
  std::vector<int> parent(static_cast<size_t>(ns), -1);
  std::vector<std::vector<int>> children(static_cast<size_t>(ns));
  std::vector<double> subtree = entries;
  std::vector<int> roots;
  for (int k = 0; k < ns; ++k) {
    const int cols = f_.super[k + 1] - f_.super[k];
    if (f_.pi[k + 1] - f_.pi[k] > cols) {
      const int p = column_owner[static_cast<size_t>(f_.s[f_.pi[k] + cols])];
      parent[static_cast<size_t>(k)] = p;
      children[static_cast<size_t>(p)].push_back(k);
      subtree[static_cast<size_t>(p)] += subtree[static_cast<size_t>(k)];
    } else {
      roots.push_back(k);
    }
  }

  std::vector<char> in_top(static_cast<size_t>(ns), 0);
  std::vector<int> frontier_bin;
  bool parallel = rows_ascending && total >= static_cast<double>(min_parallel_entries);
  if (parallel) {
    // Split the heaviest frontier subtree into its children until the bins balance.
    std::vector<int> frontier = roots;
    double top = 0.0;
    std::vector<double> load;
    for (int split = 0;; ++split) {
      frontier_bin = balance(frontier, subtree, load);
      const double heaviest_bin = *std::max_element(load.begin(), load.end());
      if (heaviest_bin <= (1.0 + kBalanceTolerance) * (total - top) / kSolveBins || split >= kMaxSplits) break;
      const auto heaviest = std::max_element(frontier.begin(), frontier.end(), [&](int a, int b) {
        return subtree[static_cast<size_t>(a)] < subtree[static_cast<size_t>(b)];
      });
      const int k = *heaviest;
      if (children[static_cast<size_t>(k)].empty() || top + entries[static_cast<size_t>(k)] > kMaxTopShare * total) break;
      in_top[static_cast<size_t>(k)] = 1;
      top += entries[static_cast<size_t>(k)];
      frontier.erase(heaviest);
      frontier.insert(frontier.end(), children[static_cast<size_t>(k)].begin(), children[static_cast<size_t>(k)].end());
    }
    // Each supernode below the frontier is in its frontier ancestor's bin (parents first: descending).
    std::vector<int> owner(static_cast<size_t>(ns), -1);
    for (size_t i = 0; i < frontier.size(); ++i) owner[static_cast<size_t>(frontier[i])] = frontier_bin[i];
    for (int k = ns - 1; k >= 0; --k)
      if (!in_top[static_cast<size_t>(k)] && owner[static_cast<size_t>(k)] < 0) owner[static_cast<size_t>(k)] = owner[static_cast<size_t>(parent[static_cast<size_t>(k)])];
    bin_nodes_.assign(kSolveBins, {});
    for (int k = 0; k < ns; ++k)
      if (in_top[static_cast<size_t>(k)])
        top_nodes_.push_back(k);
      else
        bin_nodes_[static_cast<size_t>(owner[static_cast<size_t>(k)])].push_back(k);
    top_slot_.assign(static_cast<size_t>(f_.n), -1);
    for (const int k : top_nodes_)
      for (int c = f_.super[k]; c < f_.super[k + 1]; ++c) {
        top_slot_[static_cast<size_t>(c)] = static_cast<int>(top_columns_.size());
        top_columns_.push_back(c);
      }
    private_rows_.assign(static_cast<size_t>(ns), 0);
    for (const std::vector<int>& nodes : bin_nodes_)
      for (const int k : nodes) {
        const int cols = f_.super[k + 1] - f_.super[k];
        const int* rows = f_.s + f_.pi[k] + cols;
        const int below = f_.pi[k + 1] - f_.pi[k] - cols;
        int p = 0;
        while (p < below && top_slot_[static_cast<size_t>(rows[p])] < 0) ++p;
        private_rows_[static_cast<size_t>(k)] = p;
        for (int i = p; i < below; ++i) parallel = parallel && top_slot_[static_cast<size_t>(rows[i])] >= 0;
      }
  }
  if (!parallel) {  // also where a factor broke the layout assumed above (then: serial, still right)
    bin_nodes_.clear();
    top_slot_.clear();
    top_columns_.clear();
    private_rows_.clear();
    top_nodes_.resize(static_cast<size_t>(ns));
    std::iota(top_nodes_.begin(), top_nodes_.end(), 0);
  }
  plan_top();
  entries_ = static_cast<std::size_t>(total);
  for (const int k : top_nodes_) top_entries_ += static_cast<std::size_t>(entries[static_cast<size_t>(k)]);
}

// L y = b for supernode k's columns (already holding b minus the updates of its descendants), then
// the updates to the rows below: to y for rows of its own bin (or everything, without a buffer),
// subtracted from top_buffer for top rows. Column by column, each column's part below the diagonal
// subtracted from the rows under it in one pass: most supernodes of a surface's factor are a few
// columns wide (15.5 k supernodes for 106 k rows), where the fixed cost of Eigen's general triangular
// solve and matrix-vector product per supernode outweighed streaming the entries (measured on the
// float factor of spot at 106 k vertices: 7.6 -> 5.1 ms serial, 6.7 -> 3.1 ms on two cores).
template <class Scalar>
void BasicSupernodalSolve<Scalar>::forward(int k, Scalar* y, Scalar* top_buffer, Scalar* work) const {
  const int first = f_.super[k], cols = f_.super[k + 1] - first, rows = f_.pi[k + 1] - f_.pi[k], below = rows - cols;
  const Scalar* block = f_.x + f_.px[k];
  Vector<Scalar> update(work, below);
  update.setZero();
  Scalar* own = y + first;
  for (int c = 0; c < cols; ++c) {
    const Scalar* column = block + static_cast<std::ptrdiff_t>(c) * rows;
    const Scalar value = own[c] / column[c];
    own[c] = value;
    for (int r = c + 1; r < cols; ++r) own[r] -= column[r] * value;
    update.noalias() += value * ConstVector<Scalar>(column + cols, below);
  }
  if (below == 0) return;
  const int* row = f_.s + f_.pi[k] + cols;
  const int in_bin = top_buffer ? private_rows_[static_cast<size_t>(k)] : below;
  for (int i = 0; i < in_bin; ++i) y[row[i]] -= work[i];
  for (int i = in_bin; i < below; ++i) top_buffer[top_slot_[static_cast<size_t>(row[i])]] -= work[i];
}

// L' x = y for supernode k's columns, once every row below them (its ancestors' columns) is final:
// last column first, each a dot product of its part below the diagonal with the solved values.
template <class Scalar>
void BasicSupernodalSolve<Scalar>::backward(int k, Scalar* y, Scalar* work) const {
  const int first = f_.super[k], cols = f_.super[k + 1] - first, rows = f_.pi[k + 1] - f_.pi[k], below = rows - cols;
  const Scalar* block = f_.x + f_.px[k];
  const int* row = f_.s + f_.pi[k] + cols;
  // The column's rows in one vector: its own columns' values, then the gathered ancestors'.
  Scalar* own = work;
  for (int c = 0; c < cols; ++c) own[c] = y[first + c];
  for (int i = 0; i < below; ++i) work[cols + i] = y[row[i]];
  for (int c = cols - 1; c >= 0; --c) {
    const Scalar* column = block + static_cast<std::ptrdiff_t>(c) * rows;
    const int length = rows - c - 1;
    const Scalar sum = length > 0 ? ConstVector<Scalar>(column + c + 1, length).dot(ConstVector<Scalar>(own + c + 1, length)) : Scalar(0);
    own[c] = (own[c] - sum) / column[c];
  }
  for (int c = 0; c < cols; ++c) y[first + c] = own[c];
}

template <class Scalar>
void BasicSupernodalSolve<Scalar>::plan_top() {
  if (bin_nodes_.empty()) return;  // serial: no tasks
  const int top = static_cast<int>(top_nodes_.size());
  forward_tasks_.assign(static_cast<size_t>(top), 0);
  backward_tasks_.assign(static_cast<size_t>(top), 0);
  first_flag_.assign(static_cast<size_t>(2 * top), -1);  // forward flags, then backward ones
  auto large = [&](int k) { return static_cast<double>(f_.pi[k + 1] - f_.pi[k]) * (f_.super[k + 1] - f_.super[k]) >= kLargeTopEntries; };
  for (int q = 0; q < top; ++q) {
    const int k = top_nodes_[static_cast<size_t>(q)];
    const int cols = f_.super[k + 1] - f_.super[k], rows = f_.pi[k + 1] - f_.pi[k];
    const size_t before = tasks_.size();
    if (!large(k)) {
      tasks_.push_back({TopTask::kForwardNode, q, 0, 0, -1});
    } else {
      first_flag_[static_cast<size_t>(q)] = flags_;
      for (int c = 0; c < cols; c += kBlockColumns) tasks_.push_back({TopTask::kForwardRows, q, c, std::min(c + kBlockColumns, cols), flags_++});
      for (int r = cols; r < rows; r += kBlockRows) tasks_.push_back({TopTask::kForwardRows, q, r, std::min(r + kBlockRows, rows), -1});
    }
    forward_tasks_[static_cast<size_t>(q)] = static_cast<int>(tasks_.size() - before);
  }
  for (int q = top - 1; q >= 0; --q) {
    const int k = top_nodes_[static_cast<size_t>(q)];
    const int cols = f_.super[k + 1] - f_.super[k];
    const size_t before = tasks_.size();
    if (!large(k)) {
      tasks_.push_back({TopTask::kBackwardNode, q, 0, 0, -1});
    } else {
      const int blocks = (cols + kBlockColumns - 1) / kBlockColumns;
      first_flag_[static_cast<size_t>(top + q)] = flags_;
      flags_ += blocks;
      for (int block = blocks - 1; block >= 0; --block)
        tasks_.push_back({TopTask::kBackwardColumns, q, block * kBlockColumns, std::min((block + 1) * kBlockColumns, cols),
                          first_flag_[static_cast<size_t>(top + q)] + block});
    }
    backward_tasks_[static_cast<size_t>(q)] = static_cast<int>(tasks_.size() - before);
  }
}

template <class Scalar>
void BasicSupernodalSolve<Scalar>::run_top(Scalar* y, Scalar* x) const {
  const int top = static_cast<int>(top_nodes_.size());
  std::vector<std::atomic<int>> done(static_cast<size_t>(flags_));  // value-initialised: 0
  std::vector<std::atomic<int>> forward_done(static_cast<size_t>(top)), backward_done(static_cast<size_t>(top));
  std::atomic<int> next{0};
  const int task_count = static_cast<int>(tasks_.size());
  parallel_chunks(kSolveBins, [&](int) {
    std::vector<Scalar> work(static_cast<size_t>(max_rows_)), gathered(static_cast<size_t>(max_rows_));
    for (int t = next++; t < task_count; t = next++) {
      const TopTask& task = tasks_[static_cast<size_t>(t)];
      const int q = task.top, k = top_nodes_[static_cast<size_t>(q)];
      const int first = f_.super[k], cols = f_.super[k + 1] - first, rows = f_.pi[k + 1] - f_.pi[k], below = rows - cols;
      const ConstBlock<Scalar> block(f_.x + f_.px[k], rows, cols, Eigen::OuterStride<>(rows));
      const int* row = f_.s + f_.pi[k];
      Vector<Scalar> own(y + first, cols);
      const int length = task.last - task.first;
      Vector<Scalar> acc(work.data(), length);
      const bool forward_task = task.kind == TopTask::kForwardNode || task.kind == TopTask::kForwardRows;
      // Everything before this supernode (forward: the earlier ones; backward: the later ones, or
      // the whole forward sweep for the last) is complete.
      if (forward_task && q > 0) wait_until(forward_done[static_cast<size_t>(q - 1)], forward_tasks_[static_cast<size_t>(q - 1)]);
      if (!forward_task) {
        if (q + 1 < top)
          wait_until(backward_done[static_cast<size_t>(q + 1)], backward_tasks_[static_cast<size_t>(q + 1)]);
        else
          wait_until(forward_done[static_cast<size_t>(top - 1)], forward_tasks_[static_cast<size_t>(top - 1)]);
      }
      switch (task.kind) {
        case TopTask::kForwardNode:
          forward(k, y, nullptr, work.data());
          break;
        case TopTask::kForwardRows: {
          // These rows minus L(rows, columns left of them) times those columns' solved values.
          acc.setZero();
          const int left = std::min(task.first, cols);
          for (int c = 0; c < left; c += kBlockColumns) {
            wait_until(done[static_cast<size_t>(first_flag_[static_cast<size_t>(q)] + c / kBlockColumns)], 1);
            const int width = std::min(kBlockColumns, cols - c);
            acc.noalias() += block.block(task.first, c, length, width) * own.segment(c, width);
          }
          if (task.first < cols) {
            auto part = own.segment(task.first, length);
            part -= acc;
            block.block(task.first, task.first, length, length).template triangularView<Eigen::Lower>().solveInPlace(part);
            done[static_cast<size_t>(task.flag)].store(1, std::memory_order_release);
          } else {
            for (int i = 0; i < length; ++i) y[row[task.first + i]] -= acc[i];
          }
          break;
        }
        case TopTask::kBackwardNode:
          backward(k, y, work.data());
          for (int c = first; c < first + cols; ++c) x[f_.perm[c]] = y[c];
          break;
        case TopTask::kBackwardColumns: {
          // These columns minus L(rows below them, these columns)' times those rows' values: the
          // ancestors' first, then the blocks below within the supernode, bottom up.
          acc = own.segment(task.first, length);
          if (below > 0) {
            for (int i = 0; i < below; ++i) gathered[static_cast<size_t>(i)] = y[row[cols + i]];
            acc.noalias() -= block.block(cols, task.first, below, length).transpose() * Vector<Scalar>(gathered.data(), below);
          }
          const int blocks = (cols + kBlockColumns - 1) / kBlockColumns;
          for (int b = blocks - 1; b * kBlockColumns >= task.last; --b) {
            wait_until(done[static_cast<size_t>(first_flag_[static_cast<size_t>(top + q)] + b)], 1);
            const int c = b * kBlockColumns, height = std::min(kBlockColumns, cols - c);
            acc.noalias() -= block.block(c, task.first, height, length).transpose() * own.segment(c, height);
          }
          block.block(task.first, task.first, length, length).template triangularView<Eigen::Lower>().transpose().solveInPlace(acc);
          own.segment(task.first, length) = acc;
          for (int c = task.first; c < task.last; ++c) x[f_.perm[first + c]] = y[first + c];
          done[static_cast<size_t>(task.flag)].store(1, std::memory_order_release);
          break;
        }
      }
      (forward_task ? forward_done : backward_done)[static_cast<size_t>(q)].fetch_add(1, std::memory_order_acq_rel);
    }
  });
}

template <class Scalar>
void BasicSupernodalSolve<Scalar>::solve(const Scalar* b, Scalar* x) const {
  const int n = f_.n;
  std::vector<Scalar> y(static_cast<size_t>(n));
  const int bins = static_cast<int>(bin_nodes_.size());
  std::vector<std::vector<Scalar>> buffers(static_cast<size_t>(bins));
  // Forward, the bins: each gathers its columns of P b first (a supernode updates its ancestors'
  // rows, which must already hold b), then solves its subtrees.
  if (bins > 0)
    parallel_chunks(bins, [&](int bin) {
      std::vector<Scalar> work(static_cast<size_t>(max_rows_));
      std::vector<Scalar>& buffer = buffers[static_cast<size_t>(bin)];
      buffer.assign(top_columns_.size(), Scalar(0));
      const std::vector<int>& nodes = bin_nodes_[static_cast<size_t>(bin)];
      for (const int k : nodes)
        for (int c = f_.super[k]; c < f_.super[k + 1]; ++c) y[static_cast<size_t>(c)] = b[f_.perm[c]];
      for (const int k : nodes) forward(k, y.data(), buffer.data(), work.data());
    });
  // The top: its columns of P b plus the bins' updates (in bin order), forward then backward.
  for (const int k : top_nodes_)
    for (int c = f_.super[k]; c < f_.super[k + 1]; ++c) y[static_cast<size_t>(c)] = b[f_.perm[c]];
  for (int bin = 0; bin < bins; ++bin)
    for (size_t t = 0; t < top_columns_.size(); ++t)
      y[static_cast<size_t>(top_columns_[t])] += buffers[static_cast<size_t>(bin)][t];
  if (bins > 0) {
    run_top(y.data(), x);
  } else {
    std::vector<Scalar> work(static_cast<size_t>(max_rows_));
    for (const int k : top_nodes_) forward(k, y.data(), nullptr, work.data());
    for (auto k = top_nodes_.rbegin(); k != top_nodes_.rend(); ++k) {
      backward(*k, y.data(), work.data());
      for (int c = f_.super[*k]; c < f_.super[*k + 1]; ++c) x[f_.perm[c]] = y[static_cast<size_t>(c)];
    }
  }
  // Backward, the bins: parents before children, reading only final values.
  if (bins > 0)
    parallel_chunks(bins, [&](int bin) {
      std::vector<Scalar> bin_work(static_cast<size_t>(max_rows_));
      const std::vector<int>& nodes = bin_nodes_[static_cast<size_t>(bin)];
      for (auto k = nodes.rbegin(); k != nodes.rend(); ++k) {
        backward(*k, y.data(), bin_work.data());
        for (int c = f_.super[*k]; c < f_.super[*k + 1]; ++c) x[f_.perm[c]] = y[static_cast<size_t>(c)];
      }
    });
}

template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> BasicSupernodalSolve<Scalar>::solve(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& b) const {
  if (b.size() != f_.n)
    throw std::invalid_argument("SupernodalSolve: a right-hand side of " + std::to_string(b.size()) + " rows for " +
                                std::to_string(f_.n));
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> x(f_.n);
  solve(b.data(), x.data());
  return x;
}

template class BasicSupernodalSolve<float>;
template class BasicSupernodalSolve<double>;

}  // namespace physarum
