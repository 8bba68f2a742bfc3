#include "common/supernodal_solve.hpp"

#include "common/parallel_chunks.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <numeric>

namespace physarum {
namespace {

using ConstBlock = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using Vector = Eigen::Map<Eigen::VectorXd>;

// Splitting stops once the bins are within this of perfect balance, or the top holds this share of
// the entries (it runs on one core), or after this many splits.
constexpr double kBalanceTolerance = 0.02;
constexpr double kMaxTopShare = 0.15;
constexpr int kMaxSplits = 4096;

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

SupernodalSolve::SupernodalSolve(const SupernodalFactorView& factor, std::size_t min_parallel_entries) : f_(factor) {
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
      }
  } else {
    top_nodes_.resize(static_cast<size_t>(ns));
    std::iota(top_nodes_.begin(), top_nodes_.end(), 0);
  }
  entries_ = static_cast<std::size_t>(total);
  for (const int k : top_nodes_) top_entries_ += static_cast<std::size_t>(entries[static_cast<size_t>(k)]);
}

// L y = b for supernode k's columns (already holding b minus the updates of its descendants), then
// the updates to the rows below: to y for rows of its own bin (or everything, without a buffer),
// subtracted from top_buffer for top rows.
void SupernodalSolve::forward(int k, double* y, double* top_buffer, double* work) const {
  const int first = f_.super[k], cols = f_.super[k + 1] - first, rows = f_.pi[k + 1] - f_.pi[k], below = rows - cols;
  const ConstBlock block(f_.x + f_.px[k], rows, cols, Eigen::OuterStride<>(rows));
  Vector own(y + first, cols);
  block.topRows(cols).triangularView<Eigen::Lower>().solveInPlace(own);
  if (below == 0) return;
  Vector update(work, below);
  update.noalias() = block.bottomRows(below) * own;
  const int* row = f_.s + f_.pi[k] + cols;
  const int in_bin = top_buffer ? private_rows_[static_cast<size_t>(k)] : below;
  for (int i = 0; i < in_bin; ++i) y[row[i]] -= work[i];
  for (int i = in_bin; i < below; ++i) top_buffer[top_slot_[static_cast<size_t>(row[i])]] -= work[i];
}

// L' x = y for supernode k's columns, once every row below them (its ancestors' columns) is final.
void SupernodalSolve::backward(int k, double* y, double* work) const {
  const int first = f_.super[k], cols = f_.super[k + 1] - first, rows = f_.pi[k + 1] - f_.pi[k], below = rows - cols;
  const ConstBlock block(f_.x + f_.px[k], rows, cols, Eigen::OuterStride<>(rows));
  Vector own(y + first, cols);
  if (below > 0) {
    const int* row = f_.s + f_.pi[k] + cols;
    for (int i = 0; i < below; ++i) work[i] = y[row[i]];
    own.noalias() -= block.bottomRows(below).transpose() * Vector(work, below);
  }
  block.topRows(cols).triangularView<Eigen::Lower>().transpose().solveInPlace(own);
}

Eigen::VectorXd SupernodalSolve::solve(const Eigen::VectorXd& b) const {
  const int n = f_.n;
  Eigen::VectorXd y(n), x(n);
  const int bins = static_cast<int>(bin_nodes_.size());
  std::vector<Eigen::VectorXd> buffers(static_cast<size_t>(bins));
  // Forward, the bins: each gathers its columns of P b first (a supernode updates its ancestors'
  // rows, which must already hold b), then solves its subtrees.
  if (bins > 0)
    parallel_chunks(bins, [&](int bin) {
      std::vector<double> work(static_cast<size_t>(max_rows_));
      Eigen::VectorXd& buffer = buffers[static_cast<size_t>(bin)];
      buffer.setZero(static_cast<Eigen::Index>(top_columns_.size()));
      const std::vector<int>& nodes = bin_nodes_[static_cast<size_t>(bin)];
      for (const int k : nodes)
        for (int c = f_.super[k]; c < f_.super[k + 1]; ++c) y[c] = b[f_.perm[c]];
      for (const int k : nodes) forward(k, y.data(), buffer.data(), work.data());
    });
  // The top, serially: its columns of P b plus the bins' updates (in bin order), forward then
  // backward (the last supernodes forward are the first backward, still in cache).
  std::vector<double> work(static_cast<size_t>(max_rows_));
  for (const int k : top_nodes_)
    for (int c = f_.super[k]; c < f_.super[k + 1]; ++c) y[c] = b[f_.perm[c]];
  for (int bin = 0; bin < bins; ++bin)
    for (size_t t = 0; t < top_columns_.size(); ++t) y[top_columns_[t]] += buffers[static_cast<size_t>(bin)][static_cast<Eigen::Index>(t)];
  for (const int k : top_nodes_) forward(k, y.data(), nullptr, work.data());
  for (auto k = top_nodes_.rbegin(); k != top_nodes_.rend(); ++k) {
    backward(*k, y.data(), work.data());
    for (int c = f_.super[*k]; c < f_.super[*k + 1]; ++c) x[f_.perm[c]] = y[c];
  }
  // Backward, the bins: parents before children, reading only final values.
  if (bins > 0)
    parallel_chunks(bins, [&](int bin) {
      std::vector<double> bin_work(static_cast<size_t>(max_rows_));
      const std::vector<int>& nodes = bin_nodes_[static_cast<size_t>(bin)];
      for (auto k = nodes.rbegin(); k != nodes.rend(); ++k) {
        backward(*k, y.data(), bin_work.data());
        for (int c = f_.super[*k]; c < f_.super[*k + 1]; ++c) x[f_.perm[c]] = y[c];
      }
    });
  return x;
}

}  // namespace physarum
