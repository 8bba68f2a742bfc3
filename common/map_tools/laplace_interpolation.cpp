#include "common/map_tools/laplace_interpolation.hpp"

#include "common/base/errors.hpp"
#include "common/numerics/shared_cholesky.hpp"


#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>

namespace physarum {

SurfaceComponents surface_components(const SurfaceDomain& domain) {
  // Union-find over the faces' corners (path halving, union by lower root so labels come out in
  // order of the lowest vertex).
  std::vector<int> parent(static_cast<size_t>(domain.vertex_count));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const std::array<int, 3>& f : domain.face_vertices)
    for (int k = 0; k < 3; ++k) {
      const int a = root(f[k]), b = root(f[(k + 1) % 3]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  SurfaceComponents c;
  c.label = IntrinsicVertexData<int>(static_cast<size_t>(domain.vertex_count), -1);
  for (int v = 0; v < domain.vertex_count; ++v) {
    const int r = root(v);
    if (c.label[r] < 0) c.label[r] = c.count++;
    c.label[v] = c.label[r];
  }
  return c;
}

IntrinsicVertexData<double> laplace_interpolation(const SurfaceDomain& domain, const std::vector<DirichletRegion>& regions,
                                                  const std::string& where, const std::vector<int>* ordering) {
  const int n = domain.vertex_count;
  if (regions.empty()) throw InputError(where + ": Laplace interpolation needs at least one region with a value");

  // Which region (if any) fixes each vertex; two regions may overlap only where they agree.
  std::vector<int> fixed_by(static_cast<size_t>(n), -1);
  IntrinsicVertexData<double> u(static_cast<size_t>(n), 0.0);
  for (size_t r = 0; r < regions.size(); ++r) {
    const DirichletRegion& region = regions[r];
    if (!std::isfinite(region.value))
      throw InputError(where + ": region '" + region.name + "' has the value " + std::to_string(region.value) +
                       ", which is not finite");
    if (region.vertices.empty())
      throw InputError(where + ": region '" + region.name +
                       "' holds no vertex of the surface (it must cover at least one intrinsic vertex to fix a value)");
    for (const int v : region.vertices) {
      const int before = fixed_by[static_cast<size_t>(v)];
      if (before >= 0 && regions[static_cast<size_t>(before)].value != region.value)
        throw InputError(where + ": regions '" + regions[static_cast<size_t>(before)].name + "' (value " +
                         std::to_string(regions[static_cast<size_t>(before)].value) + ") and '" + region.name + "' (value " +
                         std::to_string(region.value) + ") overlap at intrinsic vertex " + std::to_string(v) +
                         " with different values");
      fixed_by[static_cast<size_t>(v)] = static_cast<int>(r);
      u[v] = region.value;
    }
  }

  // Every component needs a fixed vertex, or its harmonic function is only defined up to a constant.
  const SurfaceComponents components = surface_components(domain);
  std::vector<int> fixed_in(static_cast<size_t>(components.count), 0), size(static_cast<size_t>(components.count), 0),
      first(static_cast<size_t>(components.count), -1);
  for (int v = 0; v < n; ++v) {
    const int c = components.label[v];
    ++size[static_cast<size_t>(c)];
    if (first[static_cast<size_t>(c)] < 0) first[static_cast<size_t>(c)] = v;
    if (fixed_by[static_cast<size_t>(v)] >= 0) ++fixed_in[static_cast<size_t>(c)];
  }
  for (int c = 0; c < components.count; ++c)
    if (fixed_in[static_cast<size_t>(c)] == 0)
      throw InputError(where + ": the surface has " + std::to_string(components.count) +
                       " connected components, and the one with intrinsic vertex " + std::to_string(first[static_cast<size_t>(c)]) +
                       " (" + std::to_string(size[static_cast<size_t>(c)]) +
                       " vertices) touches no region: its values would be undetermined (add a region there)");

  // Number the free vertices and assemble L_ff and the right-hand side -L_fb u_b.
  std::vector<int> free_index(static_cast<size_t>(n), -1);
  int free_count = 0;
  for (int v = 0; v < n; ++v)
    if (fixed_by[static_cast<size_t>(v)] < 0) free_index[static_cast<size_t>(v)] = free_count++;
  if (free_count == 0) return u;
  // L_ff straight into compressed columns: L is symmetric, so row v of the CSR form is column v, and
  // free numbering keeps vertex order, so each column's rows come out sorted (no triplet sort; at a
  // million faces the triplet assembly cost a tenth of the whole solve).
  const CsrMatrix& L = domain.laplacian;
  Eigen::SparseMatrix<double> system(free_count, free_count);
  int entries = 0;
  for (int v = 0; v < n; ++v)
    if (free_index[static_cast<size_t>(v)] >= 0)
      for (int k = L.row_start[v]; k < L.row_start[v + 1]; ++k) entries += free_index[static_cast<size_t>(L.column[k])] >= 0;
  system.resizeNonZeros(entries);
  int* column_start = system.outerIndexPtr();
  int* row = system.innerIndexPtr();
  double* value = system.valuePtr();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(free_count);
  int next = 0;
  for (int v = 0; v < n; ++v) {
    const int i = free_index[static_cast<size_t>(v)];
    if (i < 0) continue;
    column_start[i] = next;
    for (int k = L.row_start[v]; k < L.row_start[v + 1]; ++k) {
      const int j = free_index[static_cast<size_t>(L.column[k])];
      if (j >= 0) {
        if (next > column_start[i] && row[next - 1] >= j)
          throw std::logic_error("laplace_interpolation: the Laplacian's rows must have sorted, distinct columns");
        row[next] = j;
        value[next++] = L.value[k];
      } else {
        rhs[i] -= L.value[k] * u[L.column[k]];
      }
    }
  }
  column_start[free_count] = next;
  // CHOLMOD's supernodal factorization (shared_cholesky.hpp): at a million faces it is several times
  // faster than a simplicial one.
  std::optional<std::vector<int>> free_ordering;
  if (ordering) free_ordering = restricted_ordering(*ordering, free_index);
  SharedCholesky solver(system, free_ordering ? &*free_ordering : nullptr);
  try {
    solver.factor(system, "the Laplace system");
  } catch (const std::runtime_error&) {
    throw InputError(where + ": the Laplace system could not be factorized (degenerate triangles?)");
  }
  const Eigen::VectorXd solution = solver.solve(0, rhs);
  for (int v = 0; v < n; ++v)
    if (const int i = free_index[static_cast<size_t>(v)]; i >= 0) u[v] = solution[i];
  return u;
}

}  // namespace physarum
