// Segmenting a pattern: clipping each triangle at the iso-line and joining the clipped parts.
#include "common/pattern/pattern_segmentation.hpp"

#include "common/base/errors.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

namespace physarum {
namespace {

void check_field(const InputMesh& mesh, const InputVertexData<double>& field) {
  if (field.size() != static_cast<size_t>(mesh.vertex_count()))
    throw InputError(mesh.source + ": the field has " + std::to_string(field.size()) + " values for " +
                     std::to_string(mesh.vertex_count()) + " vertices");
  for (size_t v = 0; v < field.size(); ++v)
    if (!std::isfinite(field[v]))
      throw InputError(mesh.source + ": the field is not finite at vertex " + std::to_string(v));
}

// Union-find over vertices (path halving), for the components of the above-threshold graph.
int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<size_t>(v)] != v) {
    parent[static_cast<size_t>(v)] = parent[static_cast<size_t>(parent[static_cast<size_t>(v)])];
    v = parent[static_cast<size_t>(v)];
  }
  return v;
}

// Adds the exact area, first and second moments of triangle (a, b, c) to `region`:
// integral of x x^T over a triangle = A/12 (sum v v^T + (sum v)(sum v)^T).
void add_triangle(PatternRegion& region, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double area = 0.5 * (b - a).cross(c - a).norm();
  if (area == 0.0) return;
  const Eigen::Vector3d sum = a + b + c;
  region.area += area;
  region.first_moment += area / 3.0 * sum;
  region.second_moment += area / 12.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
}

}  // namespace

double default_pattern_threshold(const InputMesh& mesh, const InputVertexData<double>& field) {
  check_field(mesh, field);
  // Lumped vertex areas: a third of each incident triangle's area.
  std::vector<double> mass(field.size(), 0.0);
  for (const auto& t : mesh.triangles) {
    const auto& p = mesh.positions;
    const double area = 0.5 * (p[static_cast<size_t>(t[1])] - p[static_cast<size_t>(t[0])])
                                  .cross(p[static_cast<size_t>(t[2])] - p[static_cast<size_t>(t[0])])
                                  .norm();
    for (int k = 0; k < 3; ++k) mass[static_cast<size_t>(t[static_cast<size_t>(k)])] += area / 3.0;
  }
  const double total = std::accumulate(mass.begin(), mass.end(), 0.0);
  if (!(total > 0.0)) throw InputError(mesh.source + ": the mesh has no area, so no threshold can be chosen");
  double mean = 0.0;
  for (size_t v = 0; v < field.size(); ++v) mean += mass[v] * field[v];
  mean /= total;
  double variance = 0.0;
  for (size_t v = 0; v < field.size(); ++v) variance += mass[v] * (field[v] - mean) * (field[v] - mean);
  variance /= total;
  return mean + 0.5 * std::sqrt(variance);
}

PatternSegmentation segment_pattern(const InputMesh& mesh, const InputVertexData<double>& field, double threshold) {
  check_field(mesh, field);
  if (!std::isfinite(threshold)) throw InputError(mesh.source + ": the threshold is not finite");
  const size_t n = field.size();
  auto above = [&](int v) { return field[static_cast<size_t>(v)] > threshold; };

  // Unique edges (sorted vertex pairs) with how many triangles use each: boundary edges are used once.
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<size_t>(k)], b = t[static_cast<size_t>((k + 1) % 3)];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());

  // Components of the above-threshold graph.
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : edges)
    if (above(a) && above(b)) parent[static_cast<size_t>(find_root(parent, a))] = find_root(parent, b);

  PatternSegmentation result;
  result.threshold = threshold;
  result.vertex_region.assign(n, -1);
  std::vector<int> root_region(n, -1);
  for (size_t v = 0; v < n; ++v) {
    if (!above(static_cast<int>(v))) continue;
    const size_t root = static_cast<size_t>(find_root(parent, static_cast<int>(v)));
    if (root_region[root] < 0) {
      root_region[root] = static_cast<int>(result.regions.size());
      result.regions.emplace_back();
    }
    const int r = root_region[root];
    result.vertex_region[v] = r;
    result.regions[static_cast<size_t>(r)].vertices.push_back(static_cast<int>(v));
    result.regions[static_cast<size_t>(r)].euler_characteristic += 1;  // V
  }

  // Edges: E of the subcomplex, and which regions reach the mesh boundary.
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    const auto [a, b] = edges[i];
    if (above(a) && above(b)) result.regions[static_cast<size_t>(result.vertex_region[static_cast<size_t>(a)])].euler_characteristic -= 1;
    if (j - i == 1) {
      for (int v : {a, b})
        if (above(v)) result.regions[static_cast<size_t>(result.vertex_region[static_cast<size_t>(v)])].touches_boundary = true;
    }
    i = j;
  }

  // Triangles: clip each at the iso-line and add its clipped part to the region of its corners.
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    int region = -1, above_count = 0;
    for (int c : t)
      if (above(c)) {
        region = result.vertex_region[static_cast<size_t>(c)];
        ++above_count;
      }
    if (region < 0) continue;
    PatternRegion& r = result.regions[static_cast<size_t>(region)];
    r.faces.push_back(static_cast<int>(f));
    if (above_count == 3) r.euler_characteristic += 1;  // F

    // The clipped polygon (3 or 4 corners) and the crossing points of the iso-line.
    Eigen::Vector3d polygon[4], crossings[2];
    int corners = 0, crossing_count = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<size_t>(k)], b = t[static_cast<size_t>((k + 1) % 3)];
      const Eigen::Vector3d& pa = mesh.positions[static_cast<size_t>(a)];
      const Eigen::Vector3d& pb = mesh.positions[static_cast<size_t>(b)];
      if (above(a)) polygon[corners++] = pa;
      if (above(a) != above(b)) {
        const double fa = field[static_cast<size_t>(a)], fb = field[static_cast<size_t>(b)];
        const Eigen::Vector3d crossing = pa + (threshold - fa) / (fb - fa) * (pb - pa);
        polygon[corners++] = crossing;
        crossings[crossing_count++] = crossing;
      }
    }
    for (int k = 1; k + 1 < corners; ++k) add_triangle(r, polygon[0], polygon[k], polygon[k + 1]);
    if (crossing_count == 2) r.contour_length += (crossings[1] - crossings[0]).norm();

    const Eigen::Vector3d& p0 = mesh.positions[static_cast<size_t>(t[0])];
    const Eigen::Vector3d normal =
        (mesh.positions[static_cast<size_t>(t[1])] - p0).cross(mesh.positions[static_cast<size_t>(t[2])] - p0);
    double clipped_area = 0.0;
    for (int k = 1; k + 1 < corners; ++k) clipped_area += 0.5 * (polygon[k] - polygon[0]).cross(polygon[k + 1] - polygon[0]).norm();
    if (normal.norm() > 0.0) r.normal_sum += clipped_area * normal.normalized();
  }
  return result;
}

}  // namespace physarum
