#include "common/color/isomap_color_map.hpp"

#include "common/base/image_budget.hpp"

#include "common/base/errors.hpp"

#include <Eigen/Dense>
#include <OpenImageIO/imageio.h>
#include <Spectra/MatOp/DenseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <random>
#include <tuple>

namespace physarum {
namespace {

using Lab = std::array<double, 3>;

double distance(const Lab& a, const Lab& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// One graph node: a bin of near-identical colours.
struct ColorNode {
  Lab lab{};          // mean CIELAB
  SrgbColor srgb{};   // mean sRGB (what the spline fits)
  double pixels = 0;  // how many sampled pixels fell in the bin
  double border_pixels = 0;
};

// The pixels the map is built from: every border pixel and a fixed-seed sample of the others.
std::vector<size_t> sample_pixels(const ExemplarPixels& pixels, int max_pixels, std::uint64_t seed) {
  std::vector<size_t> border, interior;
  for (size_t i = 0; i < pixels.colors.size(); ++i)
    (!pixels.on_border.empty() && pixels.on_border[i] ? border : interior).push_back(i);
  std::vector<size_t> chosen = border;
  if (interior.size() <= static_cast<size_t>(max_pixels)) {
    chosen.insert(chosen.end(), interior.begin(), interior.end());
  } else {
    // mt19937_64's sequence is fixed by the standard, so the sample is the same everywhere; the
    // modulo bias is below 1e-14 for any image size.
    std::mt19937_64 random(seed);
    for (int k = 0; k < max_pixels; ++k) chosen.push_back(interior[random() % interior.size()]);
  }
  return chosen;
}

// Bins the sampled colours on a CIELAB grid, growing the cell until at most max_colors bins remain.
std::vector<ColorNode> merge_colors(const ExemplarPixels& pixels, const std::vector<size_t>& chosen, int max_colors) {
  std::vector<Lab> lab(chosen.size());
  for (size_t k = 0; k < chosen.size(); ++k) lab[k] = srgb_to_lab(pixels.colors[chosen[k]]);
  for (double cell = 1.0;; cell *= 1.5) {
    std::map<std::tuple<long, long, long>, ColorNode> bins;  // ordered: a deterministic node order
    for (size_t k = 0; k < chosen.size(); ++k) {
      const auto key = std::make_tuple(std::lround(std::floor(lab[k][0] / cell)), std::lround(std::floor(lab[k][1] / cell)),
                                       std::lround(std::floor(lab[k][2] / cell)));
      ColorNode& node = bins[key];
      for (int c = 0; c < 3; ++c) node.lab[c] += lab[k][c], node.srgb[c] += pixels.colors[chosen[k]][c];
      node.pixels += 1.0;
      if (!pixels.on_border.empty() && pixels.on_border[chosen[k]]) node.border_pixels += 1.0;
    }
    if (bins.size() > static_cast<size_t>(max_colors)) continue;
    std::vector<ColorNode> nodes;
    for (auto& [key, node] : bins) {
      for (int c = 0; c < 3; ++c) node.lab[c] /= node.pixels, node.srgb[c] /= node.pixels;
      nodes.push_back(node);
    }
    return nodes;
  }
}

struct Edge {
  int to;
  double length;
};

// Symmetric k-nearest-neighbour graph, then joined into one piece: for every pair of pieces the
// shortest edge between them is found in one pass, and Kruskal's algorithm over those edges adds
// the fewest, shortest edges that connect everything.
std::vector<std::vector<Edge>> neighbour_graph(const std::vector<ColorNode>& nodes, int neighbours) {
  const int n = static_cast<int>(nodes.size());
  const int k = std::min(neighbours, n - 1);
  std::vector<std::vector<Edge>> graph(n);
  auto add = [&](int a, int b, double d) {
    for (const Edge& e : graph[a])
      if (e.to == b) return;
    graph[a].push_back({b, d});
    graph[b].push_back({a, d});
  };
  std::vector<std::pair<double, int>> by_distance(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) by_distance[j] = {j == i ? std::numeric_limits<double>::infinity() : distance(nodes[i].lab, nodes[j].lab), j};
    std::partial_sort(by_distance.begin(), by_distance.begin() + k, by_distance.end());
    for (int m = 0; m < k; ++m) add(i, by_distance[m].second, by_distance[m].first);
  }

  // Pieces (union-find).
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int a) { return parent[a] == a ? a : parent[a] = root(parent[a]); };
  for (int a = 0; a < n; ++a)
    for (const Edge& e : graph[a]) parent[root(a)] = root(e.to);
  std::map<int, int> piece_of_root;
  std::vector<int> piece(n);
  for (int a = 0; a < n; ++a) piece[a] = piece_of_root.emplace(root(a), static_cast<int>(piece_of_root.size())).first->second;
  const int pieces = static_cast<int>(piece_of_root.size());
  if (pieces == 1) return graph;

  struct Bridge {
    double length = std::numeric_limits<double>::infinity();
    int a = -1, b = -1;
  };
  std::vector<Bridge> shortest(static_cast<size_t>(pieces) * pieces);
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      if (piece[a] == piece[b]) continue;
      const int pa = std::min(piece[a], piece[b]), pb = std::max(piece[a], piece[b]);
      Bridge& best = shortest[static_cast<size_t>(pa) * pieces + pb];
      const double d = distance(nodes[a].lab, nodes[b].lab);
      if (d < best.length) best = {d, a, b};
    }
  std::vector<Bridge> bridges;
  for (const Bridge& b : shortest)
    if (b.a >= 0) bridges.push_back(b);
  std::sort(bridges.begin(), bridges.end(), [](const Bridge& x, const Bridge& y) {
    return std::tie(x.length, x.a, x.b) < std::tie(y.length, y.a, y.b);
  });
  std::vector<int> piece_parent(pieces);
  std::iota(piece_parent.begin(), piece_parent.end(), 0);
  std::function<int(int)> piece_root = [&](int p) { return piece_parent[p] == p ? p : piece_parent[p] = piece_root(piece_parent[p]); };
  for (const Bridge& b : bridges) {
    const int ra = piece_root(piece[b.a]), rb = piece_root(piece[b.b]);
    if (ra == rb) continue;
    piece_parent[ra] = rb;
    add(b.a, b.b, b.length);
  }
  return graph;
}

// All-pairs shortest path lengths (Dijkstra from every node), squared.
Eigen::MatrixXd squared_geodesics(const std::vector<std::vector<Edge>>& graph) {
  const int n = static_cast<int>(graph.size());
  Eigen::MatrixXd d2(n, n);
  std::vector<double> dist(n);
  using Item = std::pair<double, int>;
  for (int source = 0; source < n; ++source) {
    std::fill(dist.begin(), dist.end(), std::numeric_limits<double>::infinity());
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist[source] = 0.0;
    queue.push({0.0, source});
    while (!queue.empty()) {
      const auto [d, a] = queue.top();
      queue.pop();
      if (d > dist[a]) continue;
      for (const Edge& e : graph[a])
        if (d + e.length < dist[e.to]) {
          dist[e.to] = d + e.length;
          queue.push({dist[e.to], e.to});
        }
    }
    for (int j = 0; j < n; ++j) d2(source, j) = dist[j] * dist[j];
  }
  return 0.5 * (d2 + d2.transpose());  // exactly symmetric
}

// Classical MDS to one dimension: the top eigenpair of B = -1/2 J D2 J.
Eigen::VectorXd mds_coordinate(const Eigen::MatrixXd& d2) {
  const Eigen::Index n = d2.rows();
  const Eigen::VectorXd row_mean = d2.rowwise().mean();
  const double grand_mean = row_mean.mean();
  Eigen::MatrixXd b = -0.5 * ((d2.colwise() - row_mean).rowwise() - row_mean.transpose());
  b.array() -= 0.5 * grand_mean;
  Eigen::VectorXd vector;
  double value = 0.0;
  if (n <= 64) {
    // Small graphs (few distinct colours): the dense solver is exact and faster than iterating.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(b);
    vector = solver.eigenvectors().col(n - 1);
    value = solver.eigenvalues()(n - 1);
  } else {
    Spectra::DenseSymMatProd<double> op(b);
    Spectra::SymEigsSolver<Spectra::DenseSymMatProd<double>> solver(op, 1, std::min<Eigen::Index>(n, 20));
    solver.init();
    solver.compute(Spectra::SortRule::LargestAlge, 1000, 1e-10);
    if (solver.info() != Spectra::CompInfo::Successful)
      throw std::runtime_error("isomap colour map: the MDS eigensolver did not converge");
    vector = solver.eigenvectors().col(0);
    value = solver.eigenvalues()(0);
  }
  return vector * std::sqrt(std::max(value, 0.0));
}

// Uniform cubic B-spline basis on [0, 1] with `intervals` intervals: the four non-zero functions at
// s, starting at index first.
void cubic_basis(double s, int intervals, int& first, std::array<double, 4>& w) {
  const double u = std::clamp(s, 0.0, 1.0) * intervals;
  first = std::min(static_cast<int>(u), intervals - 1);
  const double f = u - first;
  w = {(1 - f) * (1 - f) * (1 - f) / 6.0, (3 * f * f * f - 6 * f * f + 4) / 6.0,
       (-3 * f * f * f + 3 * f * f + 3 * f + 1) / 6.0, f * f * f / 6.0};
}

}  // namespace

std::array<double, 3> srgb_to_lab(const SrgbColor& color) {
  double linear[3];
  for (int c = 0; c < 3; ++c) {
    const double v = color[c];
    linear[c] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  }
  const double x = (0.4124564 * linear[0] + 0.3575761 * linear[1] + 0.1804375 * linear[2]) / 0.95047;
  const double y = 0.2126729 * linear[0] + 0.7151522 * linear[1] + 0.0721750 * linear[2];
  const double z = (0.0193339 * linear[0] + 0.1191920 * linear[1] + 0.9503041 * linear[2]) / 1.08883;
  constexpr double delta = 6.0 / 29.0;
  auto f = [&](double t) { return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29.0; };
  return {116.0 * f(y) - 16.0, 500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

ExemplarPixels read_exemplar_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path + ": cannot read the image: " + OIIO::geterror());
  const OIIO::ImageSpec spec = in->spec();
  const int w = spec.width, h = spec.height, channels = spec.nchannels;
  if (w < 1 || h < 1 || channels < 1) throw InputError(path + ": the image is empty");
  check_image_budget(w, h, path, "colour-map exemplar");
  std::vector<std::uint8_t> data(static_cast<size_t>(w) * h * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, data.data()))
    throw InputError(path + ": cannot read the image: " + in->geterror());
  in->close();
  // Grey (+alpha) images repeat their one colour channel; alpha is the channel OpenImageIO names so.
  const int alpha = spec.alpha_channel;
  const int colour_channels = channels >= 3 ? 3 : 1;
  const int band = std::max(1, static_cast<int>(std::lround(0.02 * std::min(w, h))));
  // Large photographs keep the interior pixels of a regular grid only (at most about 250k), so the
  // colour list stays a few MB; the random sample of isomap_color_map is drawn from those.
  const int stride = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(w) * h / 250000.0))));
  ExemplarPixels pixels;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool on_border = x < band || y < band || x >= w - band || y >= h - band;
      if (!on_border && (x % stride != 0 || y % stride != 0)) continue;
      const std::uint8_t* p = &data[(static_cast<size_t>(y) * w + x) * channels];
      if (alpha >= 0 && alpha < channels && p[alpha] < 128) continue;  // transparent: not part of the picture
      SrgbColor c{};
      for (int ch = 0; ch < 3; ++ch) c[ch] = p[colour_channels == 3 ? ch : 0] / 255.0;
      pixels.colors.push_back(c);
      pixels.on_border.push_back(on_border);
    }
  if (pixels.colors.empty()) throw InputError(path + ": the image has no opaque pixel");
  return pixels;
}

IsomapColorMap isomap_color_map(const ExemplarPixels& pixels, const std::string& name, const std::string& source,
                               const IsomapOptions& options) {
  if (options.stops < 2) throw InputError(source + ": a colour map needs at least 2 stops, asked for " + std::to_string(options.stops));
  if (!pixels.on_border.empty() && pixels.on_border.size() != pixels.colors.size())
    throw std::invalid_argument("isomap_colormap: on_border must be empty or match colors");
  const std::vector<ColorNode> nodes =
      merge_colors(pixels, sample_pixels(pixels, std::max(1, options.max_pixels), options.seed), std::max(2, options.max_colors));
  const int n = static_cast<int>(nodes.size());
  if (n < 2)
    throw InputError(source + ": the image has only one colour; a colour map needs at least two distinct colours");

  const Eigen::VectorXd coordinate = mds_coordinate(squared_geodesics(neighbour_graph(nodes, std::max(1, options.neighbours))));
  const double lo = coordinate.minCoeff(), hi = coordinate.maxCoeff();
  if (!(hi > lo)) throw InputError(source + ": the colours do not spread along any direction (degenerate exemplar)");
  std::vector<double> s(n);
  for (int i = 0; i < n; ++i) s[i] = (coordinate(i) - lo) / (hi - lo);

  // Background: most border pixels, else most pixels; ties go to the lower index (deterministic).
  const bool has_border = std::any_of(nodes.begin(), nodes.end(), [](const ColorNode& c) { return c.border_pixels > 0; });
  int background = 0;
  for (int i = 1; i < n; ++i) {
    const double score = has_border ? nodes[i].border_pixels : nodes[i].pixels;
    const double best = has_border ? nodes[background].border_pixels : nodes[background].pixels;
    if (score > best) background = i;
  }
  if (s[background] > 0.5)
    for (double& v : s) v = 1.0 - v;

  // Penalised least squares per channel: (B^T W B + lambda D^T D) c = B^T W y.
  constexpr int kIntervals = 24;
  constexpr int kCoefficients = kIntervals + 3;
  const double total = std::accumulate(nodes.begin(), nodes.end(), 0.0, [](double a, const ColorNode& c) { return a + c.pixels; });
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(kCoefficients, kCoefficients);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(kCoefficients, 3);
  for (int i = 0; i < n; ++i) {
    int first;
    std::array<double, 4> w;
    cubic_basis(s[i], kIntervals, first, w);
    const double weight = nodes[i].pixels / total;
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) normal(first + a, first + b) += weight * w[a] * w[b];
      for (int c = 0; c < 3; ++c) rhs(first + a, c) += weight * w[a] * nodes[i].srgb[c];
    }
  }
  // A small penalty: the data decide wherever there are pixels; across parameter ranges without
  // any, the curve continues straight instead of oscillating.
  constexpr double kLambda = 1e-6;
  Eigen::MatrixXd second_difference = Eigen::MatrixXd::Zero(kCoefficients - 2, kCoefficients);
  for (int r = 0; r < kCoefficients - 2; ++r) second_difference(r, r) = 1, second_difference(r, r + 1) = -2, second_difference(r, r + 2) = 1;
  normal += kLambda * second_difference.transpose() * second_difference;
  const Eigen::MatrixXd coefficients = normal.ldlt().solve(rhs);

  std::vector<ColorStop> stops(options.stops);
  for (int k = 0; k < options.stops; ++k) {
    const double t = static_cast<double>(k) / (options.stops - 1);
    int first;
    std::array<double, 4> w;
    cubic_basis(t, kIntervals, first, w);
    stops[k].position = t;
    for (int c = 0; c < 3; ++c) {
      double v = 0.0;
      for (int a = 0; a < 4; ++a) v += w[a] * coefficients(first + a, c);
      stops[k].color[c] = std::clamp(v, 0.0, 1.0);
    }
  }
  return {ColorMap(name, std::move(stops)), nodes[background].srgb, n};
}

IsomapColorMap isomap_color_map_from_image(const std::string& path, const IsomapOptions& options) {
  return isomap_color_map(read_exemplar_image(path), std::filesystem::path(path).stem().string(), path, options);
}

}  // namespace physarum
