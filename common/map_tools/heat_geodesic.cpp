#include "common/map_tools/heat_geodesic.hpp"

#include "common/map_tools/boundary_outflow.hpp"
#include "common/base/errors.hpp"
#include "common/base/parallel_chunks.hpp"
#include "common/numerics/shared_cholesky.hpp"
#include "common/surface/surface_pieces.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace physarum {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// A heat solution far from the seeds is tiny: one backward Euler step of length t = h^2 decays by
// about e per edge, so pole to pole on a sphere of a million faces (~700 edges) it spans ~300 decades,
// and twice that underflows any double. So the heat is solved in levels, each with its own scale:
// value[v] stands for value[v] * exp(-log_scale[v]).
struct ScaledHeat {
  Eigen::VectorXd value;
  std::vector<double> log_scale;
};

// Each level is scaled so that its largest values sit near kTop, and resolves every value down to
// kLowest, 18 decades above the smallest normal double (2.2e-308): 440 decades per solve, so a
// sphere of 1.3 M faces (level-8 icosphere, ~300 decades pole to pole) needs one level and a flat
// strip ~1000 edges long two. The tiny values are as accurate as the large ones for the gradient's
// direction: measured on that sphere, one level (resolving ~1e-290 relative) and three levels
// (1e-100 each) give the same distances (max error 0.295 % of pi both). Once they looked
// inaccurate below ~1e-165 of the top: that was |grad u| underflowing when squared, not the solve
// (the divergence below now scales the gradient before normalising it). kTop leaves 150 decades of
// headroom: nothing here squares a heat value.
constexpr double kTop = 1e150;
constexpr double kLowest = 1e-290;
constexpr int kMaxLevels = 64;

// Solves A u = rhs in levels (rhs scaled by the caller so that u peaks near kTop). Level 0 is the
// plain solve; vertices with u >= kLowest are resolved. The rest, C, is exactly A^{-1} f with
// f = A (u 1_C): since A u = rhs, f is supported on the band where C meets the resolved set K
// (f_i = rhs_i - sum_{j in K} A_ij u_j for i in C, f_i = sum_{j in C} A_ij u_j for i in K), so it
// needs only values next to K, which are accurate. Scaled by kTop / kLowest the next solve brings
// C's values back up, and each level is as accurate as the first (tests/test_geodesic_heat.cpp: a
// strip long enough to need three levels).
ScaledHeat heat_in_levels(const CholeskyFactor& solver, const SparseMatrix& a, Eigen::VectorXd rhs) {
  const int n = static_cast<int>(a.rows());
  ScaledHeat out{Eigen::VectorXd::Zero(n), std::vector<double>(static_cast<size_t>(n), 0.0)};
  std::vector<char> known(static_cast<size_t>(n), 0);
  int known_count = 0;
  double log_scale = 0.0;
  for (int level = 0; level < kMaxLevels && known_count < n; ++level) {
    const Eigen::VectorXd x = solver.solve(rhs);
    double top = 0.0;
    for (int v = 0; v < n; ++v)
      if (!known[static_cast<size_t>(v)]) top = std::max(top, x[v]);
    if (!(top > 0.0) || !std::isfinite(top)) break;  // no heat reaches the rest (Dirichlet, boundary seeds only)
    for (int v = 0; v < n; ++v)
      if (!known[static_cast<size_t>(v)] && x[v] >= kLowest) {
        known[static_cast<size_t>(v)] = 1;
        out.value[v] = x[v];
        out.log_scale[static_cast<size_t>(v)] = log_scale;
        ++known_count;
      }
    if (known_count == n) break;
    Eigen::VectorXd next = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      const bool i_known = known[static_cast<size_t>(i)] != 0;
      double sum = 0.0;
      for (SparseMatrix::InnerIterator it(a, i); it; ++it) {  // column i = row i (A is symmetric)
        const int j = static_cast<int>(it.row());
        if (j != i && (known[static_cast<size_t>(j)] != 0) != i_known) sum += it.value() * x[j];
      }
      // kTop / kLowest overflows a double: two factors, the first bringing the band to ~1.
      next[i] = (i_known ? sum : rhs[i] - sum) / kLowest * kTop;
    }
    rhs = std::move(next);
    log_scale += std::log(kTop) - std::log(kLowest);
  }
  return out;
}

// `a` with the rows and columns of `removed` vertices replaced by the identity, keeping every stored
// entry (explicit zeros), so that the pattern stays the one analysed.
SparseMatrix with_identity_rows(SparseMatrix a, const std::vector<char>& removed) {
  for (int col = 0; col < a.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(a, col); it; ++it)
      if (removed[static_cast<size_t>(col)] || removed[static_cast<size_t>(it.row())]) it.valueRef() = it.row() == col ? 1.0 : 0.0;
  return a;
}

// ---- the steps of distance() ----------------------------------------------------------------------

// Seeds inside and on the boundary: a seed on the boundary keeps its Neumann value (u = 0 on the
// rest of the boundary), so the Dirichlet solution has the heat leaving it into the surface too.
// The Dirichlet solution is averaged into the Neumann one `u`.
void average_with_dirichlet(ScaledHeat& u, const Eigen::VectorXd& delta, const std::vector<int>& seeds,
                            const CholeskyFactor& dirichlet, const SparseMatrix& dirichlet_matrix,
                            const SparseMatrix& heat_matrix, const std::vector<char>& on_boundary) {
  const int n = static_cast<int>(delta.size());
  // Its couplings to interior vertices move to the right-hand side (they are zero in the matrix).
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (const int s : seeds) {
    if (!on_boundary[static_cast<size_t>(s)]) {
      rhs[s] += delta[s];
      continue;
    }
    rhs[s] = u.value[s];  // level 0: a seed is among the largest values
    for (SparseMatrix::InnerIterator it(heat_matrix, s); it; ++it)
      if (!on_boundary[static_cast<size_t>(it.row())]) rhs[it.row()] -= it.value() * u.value[s];
  }
  // The average, at the Neumann solution's scale: u_D <= u_N (the boundary drains heat), so the
  // Dirichlet value can only underflow there, never overflow.
  const ScaledHeat d = heat_in_levels(dirichlet, dirichlet_matrix, rhs);
  for (int v = 0; v < n; ++v) {
    const double dirichlet_value =
        d.value[v] == 0.0 ? 0.0 : d.value[v] * std::exp(u.log_scale[static_cast<size_t>(v)] - d.log_scale[static_cast<size_t>(v)]);
    u.value[v] = 0.5 * (u.value[v] + dirichlet_value);
  }
}

// 2 + 3. The unit field X = -grad u / |grad u| per face, and its integrated divergence per vertex
// (Crane et al. Sec. 3.2: b_i = 1/2 sum over faces of cot(theta_1) e_1.X + cot(theta_2) e_2.X, e the
// edges leaving i, theta the angles opposite them), except in the faces around a lone seed corner.
//
// There the distance is a cone, and phi (the piecewise linear function whose gradient fits X best)
// cannot follow it: the interpolant of a cone has a gradient LONGER than 1 in those faces
// (1 / cos(theta/2) for an apex angle theta: 1.15 on an equilateral fan), so a unit field makes the
// first ring rise too little from the seed, and everything beyond inherits the deficit as an offset
// (measured on the unit icosphere of shape:sphere: first ring ~0.17 h too low, mean error -0.013
// rad, i.e. most of the 0.93-1.09 % of pi). Those faces are flat and touch the seed, so the distance
// at their corners is known: 0 at the seed and the edge length to the nearest adjacent seed at the
// others; X there is the gradient of that linear function. Faces with three seed corners lie
// inside a region of seeds, where the distance is 0, so X = 0 there (the heat's field flows outward
// from the region's middle and made the result the distance from that middle: 0.47 on the rim of a
// seeded cap of radius 0.5). Faces with two seed corners keep the heat's field: a seed edge is a
// piece of a source curve, whose distance grows at unit rate across it.

// Per vertex beside a seed (not a seed itself): the length of the shortest face side to a seed.
std::vector<double> distance_next_to_seed(const SurfaceDomain& domain, const std::vector<char>& is_seed) {
  std::vector<double> next_to_seed(static_cast<size_t>(domain.vertex_count), std::numeric_limits<double>::infinity());
  for (int face = 0; face < domain.face_count; ++face) {
    const auto& p = domain.face_corners[face];
    const auto& v = domain.face_vertices[face];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (is_seed[static_cast<size_t>(v[a])] && !is_seed[static_cast<size_t>(v[b])]) {
          double& d = next_to_seed[static_cast<size_t>(v[b])];
          d = std::min(d, (p[a] - p[b]).norm());
        }
  }
  return next_to_seed;
}

// X on a face with one seed corner: the gradient of the distance's interpolant there.
Eigen::Vector2d cone_field(const std::array<Eigen::Vector2d, 3>& p, const std::array<int, 3>& v,
                           const std::vector<char>& is_seed, const std::vector<double>& next_to_seed) {
  Eigen::Vector2d cone = Eigen::Vector2d::Zero();  // the interpolant's gradient times 2A
  for (int k = 0; k < 3; ++k) {
    if (is_seed[static_cast<size_t>(v[k])]) continue;
    const Eigen::Vector2d e = p[(k + 2) % 3] - p[(k + 1) % 3];
    cone += next_to_seed[static_cast<size_t>(v[k])] * Eigen::Vector2d(-e.y(), e.x());
  }
  const Eigen::Vector2d a = p[1] - p[0], b = p[2] - p[0];
  return Eigen::Vector2d(cone / (a.x() * b.y() - a.y() * b.x()));  // signed 2A: the layout's orientation cancels
}

// X = -grad u / |grad u| on a face, or nothing where no heat reached it.
std::optional<Eigen::Vector2d> heat_field(const std::array<Eigen::Vector2d, 3>& p, const std::array<int, 3>& v,
                                          const ScaledHeat& u) {
  // The corners in one scale. On one level (nearly every face) their values are that; a face
  // across levels is taken in logarithms with its largest corner at 1 (one level's scale differs
  // from the next by 440 decades, so no product of a value and a scale factor is safe there).
  std::array<double, 3> corner_heat{u.value[v[0]], u.value[v[1]], u.value[v[2]]};
  const double level0 = u.log_scale[static_cast<size_t>(v[0])];
  if (level0 != u.log_scale[static_cast<size_t>(v[1])] || level0 != u.log_scale[static_cast<size_t>(v[2])]) {
    std::array<double, 3> log_heat{};
    double largest = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      log_heat[k] = corner_heat[k] > 0.0 ? std::log(corner_heat[k]) - u.log_scale[static_cast<size_t>(v[k])]
                                         : -std::numeric_limits<double>::infinity();
      largest = std::max(largest, log_heat[k]);
    }
    for (int k = 0; k < 3; ++k) corner_heat[k] = corner_heat[k] > 0.0 ? std::exp(log_heat[k] - largest) : 0.0;
  }
  Eigen::Vector2d grad = Eigen::Vector2d::Zero();  // times 2A: only the direction is used
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d e = p[(k + 2) % 3] - p[(k + 1) % 3];
    grad += corner_heat[k] * Eigen::Vector2d(-e.y(), e.x());
  }
  // Only the direction counts: scaled to its largest component first, because far from the
  // seeds the components can be ~1e-290 and their squares underflow.
  const double largest = grad.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) return std::nullopt;  // no heat reached this face: no direction
  return Eigen::Vector2d(-(grad / largest).normalized());
}

// The unit field X on one face, or nothing where no heat reached it (or inside a seed region).
std::optional<Eigen::Vector2d> unit_field_on(const SurfaceDomain& domain, const std::vector<char>& is_seed,
                                             const std::vector<double>& next_to_seed, const ScaledHeat& u, int face) {
  const auto& p = domain.face_corners[face];
  const auto& v = domain.face_vertices[face];
  const int seed_corners = is_seed[static_cast<size_t>(v[0])] + is_seed[static_cast<size_t>(v[1])] + is_seed[static_cast<size_t>(v[2])];
  if (seed_corners == 3) return std::nullopt;  // inside a region of seeds: X = grad 0 = 0
  if (seed_corners == 1) return cone_field(p, v, is_seed, next_to_seed);
  return heat_field(p, v, u);
}

// The integrated divergence of X per vertex; `replaced` (empty, or per face an index into
// `outflow`, -1 for none) overrides field_on.
//
// Large meshes: faces in a fixed number of chunks, each summing into its own vector, added in chunk
// order, so the cores share the pass (70 ms at 1.3 M faces on one) and the result does not depend
// on the threads. Small ones: one chunk, no thread started.
template <class FieldOn>
Eigen::VectorXd integrated_divergence(const SurfaceDomain& domain, const std::vector<std::array<double, 3>>& corner_cot,
                                      const std::vector<FaceDirectionOverride>& outflow, const std::vector<int>& replaced,
                                      const FieldOn& field_on) {
  const int n = domain.vertex_count;
  const int chunks = domain.face_count < 65536 ? 1 : 4;
  std::vector<Eigen::VectorXd> partial(static_cast<size_t>(chunks), Eigen::VectorXd::Zero(n));
  parallel_chunks(chunks, [&](int chunk) {
    Eigen::VectorXd& divergence = partial[static_cast<size_t>(chunk)];
    const int first = static_cast<int>(static_cast<long long>(domain.face_count) * chunk / chunks);
    const int last = static_cast<int>(static_cast<long long>(domain.face_count) * (chunk + 1) / chunks);
    for (int face = first; face < last; ++face) {
      std::optional<Eigen::Vector2d> field;
      if (!replaced.empty() && replaced[static_cast<size_t>(face)] >= 0) field = outflow[static_cast<size_t>(replaced[static_cast<size_t>(face)])].direction;
      else field = field_on(face);
      if (!field) continue;
      const Eigen::Vector2d& x = *field;
      const auto& p = domain.face_corners[face];
      const auto& v = domain.face_vertices[face];
      const auto& cot = corner_cot[static_cast<size_t>(face)];
      for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        divergence[v[i]] += 0.5 * (cot[k] * (p[j] - p[i]).dot(x) + cot[j] * (p[k] - p[i]).dot(x));
      }
    }
  });
  Eigen::VectorXd divergence = std::move(partial[0]);
  for (int chunk = 1; chunk < chunks; ++chunk) divergence += partial[static_cast<size_t>(chunk)];
  return divergence;
}

// L phi = -b (L is the positive semi-definite Laplacian, Crane's L_C = -L).
IntrinsicVertexData<double> solve_poisson(const CholeskyFactor& poisson, const std::vector<char>& pinned,
                                          const Eigen::VectorXd& divergence) {
  const int n = static_cast<int>(divergence.size());
  Eigen::VectorXd rhs = -divergence;
  for (int v = 0; v < n; ++v)
    if (pinned[static_cast<size_t>(v)]) rhs[v] = 0.0;
  IntrinsicVertexData<double> phi(static_cast<size_t>(n), 0.0);
  Eigen::Map<Eigen::VectorXd>(phi.data(), n) = poisson.solve(rhs);
  return phi;
}

// Per piece: the smallest value over its seeds becomes 0.
void shift_to_zero_at_seeds(IntrinsicVertexData<double>& phi, const std::vector<int>& seeds, const SurfacePieces& pieces) {
  const int n = static_cast<int>(phi.size());
  std::vector<double> shift(static_cast<size_t>(pieces.count()), std::numeric_limits<double>::infinity());
  for (const int s : seeds) {
    double& m = shift[static_cast<size_t>(pieces.piece_of_vertex[static_cast<size_t>(s)])];
    m = std::min(m, phi[static_cast<size_t>(s)]);
  }
  for (int v = 0; v < n; ++v)
    phi[static_cast<size_t>(v)] = std::max(0.0, phi[static_cast<size_t>(v)] - shift[static_cast<size_t>(pieces.piece_of_vertex[static_cast<size_t>(v)])]);
}

}  // namespace

struct HeatGeodesicSolver::Factorizations {
  SurfacePieces pieces;
  // M + tL (Neumann), the same with identity rows on the boundary (Dirichlet: u = 0 there), and L
  // with identity rows at one pinned vertex per piece, all with one pattern and one analysis.
  SparseMatrix heat_matrix, dirichlet_matrix;
  std::unique_ptr<SharedCholesky> cholesky;
  CholeskyFactor heat, dirichlet, poisson;  // dirichlet.index < 0 without boundary
  std::vector<char> on_boundary, pinned;
  bool boundary = false;
  // Per face and corner k: cot of the interior angle at k (the divergence's weights).
  std::vector<std::array<double, 3>> corner_cot;
};

double mean_intrinsic_edge_length(const SurfaceDomain& domain) {
  double sum = 0.0;
  long long count = 0;
  for (int f = 0; f < domain.face_count; ++f)
    for (int i = 0; i < 3; ++i) {
      const int g = domain.face_neighbour[f][i];
      // An interior edge is seen from both faces: count it from the lower halfedge only.
      if (g >= 0 && 3 * g + domain.neighbour_edge[f][i] < 3 * f + i) continue;
      sum += (domain.face_corners[f][(i + 1) % 3] - domain.face_corners[f][i]).norm();
      ++count;
    }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

HeatGeodesicSolver::HeatGeodesicSolver(const SurfaceDomain& domain, double time_factor, const std::vector<int>* ordering)
    : domain_(domain), factors_(std::make_unique<Factorizations>()) {
  if (!(time_factor > 0.0) || !std::isfinite(time_factor))
    throw std::invalid_argument("HeatGeodesicSolver: the time factor must be finite and > 0");
  mean_edge_length_ = mean_intrinsic_edge_length(domain);
  time_ = time_factor * mean_edge_length_ * mean_edge_length_;
  Factorizations& f = *factors_;
  const int n = domain.vertex_count;
  f.pieces = surface_pieces(domain);

  SparseMatrix& heat = f.heat_matrix;
  heat = time_ * SparseMatrix(domain.laplacian.to_eigen());  // symmetric: storage order is free
  for (int v = 0; v < n; ++v) heat.coeffRef(v, v) += domain.vertex_mass[static_cast<size_t>(v)];
  heat.makeCompressed();
  f.cholesky = std::make_unique<SharedCholesky>(heat, ordering);
  auto factor = [&](const SparseMatrix& a, const char* what) {
    try {
      return CholeskyFactor{f.cholesky.get(), f.cholesky->factor(a, what)};
    } catch (const std::runtime_error& error) {
      throw InputError(std::string("heat method: ") + error.what() + " (the intrinsic triangulation has degenerate faces)");
    }
  };
  f.heat = factor(heat, "M + tL");

  f.on_boundary.assign(static_cast<size_t>(n), 0);
  for (int face = 0; face < domain.face_count; ++face)
    for (int i = 0; i < 3; ++i)
      if (domain.face_neighbour[face][i] < 0) {
        f.on_boundary[static_cast<size_t>(domain.face_vertices[face][i])] = 1;
        f.on_boundary[static_cast<size_t>(domain.face_vertices[face][(i + 1) % 3])] = 1;
      }
  f.boundary = std::find(f.on_boundary.begin(), f.on_boundary.end(), 1) != f.on_boundary.end();
  if (f.boundary) {
    f.dirichlet_matrix = with_identity_rows(heat, f.on_boundary);
    f.dirichlet = factor(f.dirichlet_matrix, "M + tL (Dirichlet)");
  }

  // L is singular (constants per piece); pinning one vertex per piece leaves a positive definite
  // system whose solution is exact (the divergence sums to zero over every piece). L is taken from
  // the heat matrix's own entries so that the pattern is the analysed one: off the diagonal
  // L_ij = heat_ij / t, on it minus the sum of the others (rows of L sum to zero).
  f.pinned.assign(static_cast<size_t>(n), 0);
  std::vector<char> piece_pinned(static_cast<size_t>(f.pieces.count()), 0);
  for (int v = 0; v < n; ++v) {
    char& p = piece_pinned[static_cast<size_t>(f.pieces.piece_of_vertex[static_cast<size_t>(v)])];
    if (!p) p = f.pinned[static_cast<size_t>(v)] = 1;
  }
  SparseMatrix poisson = heat;
  for (int col = 0; col < n; ++col) {
    double off_diagonal = 0.0;
    for (SparseMatrix::InnerIterator it(poisson, col); it; ++it)
      if (it.row() != col) off_diagonal += it.valueRef() /= time_;
    for (SparseMatrix::InnerIterator it(poisson, col); it; ++it)
      if (it.row() == col) it.valueRef() = -off_diagonal;
  }
  f.poisson = factor(with_identity_rows(std::move(poisson), f.pinned), "L");

  f.corner_cot.resize(static_cast<size_t>(domain.face_count));
  for (int face = 0; face < domain.face_count; ++face) {
    const auto& p = domain.face_corners[face];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      f.corner_cot[static_cast<size_t>(face)][k] = a.dot(b) / std::abs(a.x() * b.y() - a.y() * b.x());
    }
  }
}

HeatGeodesicSolver::~HeatGeodesicSolver() = default;

bool HeatGeodesicSolver::has_boundary() const { return factors_->boundary; }

IntrinsicVertexData<double> HeatGeodesicSolver::distance(const std::vector<int>& seeds) const {
  const Factorizations& f = *factors_;
  const int n = domain_.vertex_count;
  if (seeds.empty()) throw InputError("heat method: the seed set is empty");
  for (const int s : seeds)
    if (s < 0 || s >= n)
      throw InputError("heat method: seed " + std::to_string(s) + " is no intrinsic vertex (0.." + std::to_string(n - 1) + ")");
  require_seed_in_every_piece(f.pieces, seeds, "heat method");

  // 1. Heat flow from the seeds' indicator.
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(n);
  // kTop times the seed's mass: the solution there is about delta_s / m_s, i.e. near kTop.
  for (const int s : seeds) delta[s] = kTop * domain_.vertex_mass[static_cast<size_t>(s)];
  ScaledHeat u = heat_in_levels(f.heat, f.heat_matrix, delta);
  // With every seed on the boundary the Dirichlet solution (u = 0 on the boundary) holds the seeds
  // themselves at 0: there is no Dirichlet heat to average with, and the Neumann solution is used
  // alone, its one defect (level sets turned to meet the boundary square where the geodesics leave
  // through it) corrected in the field below. Measured on shape:square, which the earlier average
  // with a Dirichlet solution holding the seeds at their Neumann values did no better than Neumann
  // alone: from a corner 2.45 -> 0.95 % of the diagonal, from the middle of a side 1.21 -> 0.81 %,
  // from a whole side 2.81 -> 0.61 % (tests/test_geodesic_heat.cpp).
  const bool neumann_only =
      f.boundary && std::all_of(seeds.begin(), seeds.end(), [&](int s) { return f.on_boundary[static_cast<size_t>(s)] != 0; });
  if (f.boundary && !neumann_only)
    average_with_dirichlet(u, delta, seeds, f.dirichlet, f.dirichlet_matrix, f.heat_matrix, f.on_boundary);

  // 2 + 3. The unit field X per face (the comment above unit_field_on says which) and its
  // integrated divergence per vertex.
  std::vector<char> is_seed(static_cast<size_t>(n), 0);
  for (const int s : seeds) is_seed[static_cast<size_t>(s)] = 1;
  const std::vector<double> next_to_seed = distance_next_to_seed(domain_, is_seed);
  auto field_on = [&](int face) { return unit_field_on(domain_, is_seed, next_to_seed, u, face); };
  // With the Neumann heat alone, the boundary faces where the geodesics leave the surface take the
  // direction from the interior (common/map_tools/boundary_outflow.hpp); replaced[face] indexes `outflow`.
  std::vector<FaceDirectionOverride> outflow;
  std::vector<int> replaced;
  if (neumann_only) {
    outflow = outflow_directions(domain_, f.on_boundary, is_seed, field_on);
    replaced.assign(static_cast<size_t>(domain_.face_count), -1);
    for (size_t i = 0; i < outflow.size(); ++i) replaced[static_cast<size_t>(outflow[i].face)] = static_cast<int>(i);
  }
  const Eigen::VectorXd divergence = integrated_divergence(domain_, f.corner_cot, outflow, replaced, field_on);

  IntrinsicVertexData<double> phi = solve_poisson(f.poisson, f.pinned, divergence);
  shift_to_zero_at_seeds(phi, seeds, f.pieces);
  return phi;
}

}  // namespace physarum
