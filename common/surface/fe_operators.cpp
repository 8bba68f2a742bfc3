#include "common/surface/fe_operators.hpp"

#include "common/base/errors.hpp"
#include "common/surface/surface_domain.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace physarum {

double triangle_area_from_lengths(const std::array<double, 3>& l) {
  // Kahan, "Miscalculating area and angles of a needle-like triangle": sort a >= b >= c and keep
  // the parentheses; this stays accurate for needles where the textbook Heron formula cancels.
  std::array<double, 3> s = l;
  std::sort(s.begin(), s.end(), [](double x, double y) { return x > y; });
  const double a = s[0], b = s[1], c = s[2];
  const double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  if (!(product > 0.0)) return 0.0;  // degenerate, violated triangle inequality, or NaN input
  return 0.25 * std::sqrt(product);
}

std::array<Eigen::Vector2d, 3> layout_triangle(const std::array<double, 3>& l) {
  const double area = triangle_area_from_lengths(l);
  // Corner 2 from the law of cosines (x) and the height over edge 0 (y = 2A / l0), so that y is
  // accurate even for very flat triangles.
  const double x = (l[0] * l[0] + l[2] * l[2] - l[1] * l[1]) / (2.0 * l[0]);
  const double y = 2.0 * area / l[0];
  return {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(l[0], 0.0), Eigen::Vector2d(x, y)};
}

std::array<double, 3> corner_cotangents(const std::array<double, 3>& l) {
  const double four_area = 4.0 * triangle_area_from_lengths(l);
  std::array<double, 3> cot{};
  for (int k = 0; k < 3; ++k) {
    // Corner k sits between halfedges k (outgoing) and k+2 (incoming) and faces halfedge k+1.
    const double adjacent1 = l[k], adjacent2 = l[(k + 2) % 3], opposite = l[(k + 1) % 3];
    cot[k] = (adjacent1 * adjacent1 + adjacent2 * adjacent2 - opposite * opposite) / four_area;
  }
  return cot;
}

void validate_face_lengths(const IntrinsicMesh& mesh, int face, const char* source) {
  const std::array<double, 3>& l = mesh.edge_lengths[face];
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(l[i]) || !(l[i] > 0.0))
      throw InputError(std::string(source) + ": face " + std::to_string(face) + " has edge " + std::to_string(i) +
                       " of length " + std::to_string(l[i]) + " (must be finite and positive)");
  for (int i = 0; i < 3; ++i)
    if (!(l[i] < l[(i + 1) % 3] + l[(i + 2) % 3]))
      throw InputError(std::string(source) + ": face " + std::to_string(face) + " violates the triangle inequality (edge " +
                       std::to_string(i) + " of length " + std::to_string(l[i]) + " >= sum of the other two)");
  if (!(triangle_area_from_lengths(l) > 0.0))
    throw InputError(std::string(source) + ": face " + std::to_string(face) + " has non-positive area");
}

std::vector<std::array<double, 3>> cotan_edge_weights(const IntrinsicMesh& mesh) {
  const int nf = mesh.face_count();
  // First each halfedge's own half: cot of the angle opposite it in its face, over two.
  std::vector<std::array<double, 3>> half(nf);
  for (int f = 0; f < nf; ++f) {
    validate_face_lengths(mesh, f);
    const std::array<double, 3> cot = corner_cotangents(mesh.edge_lengths[f]);
    for (int i = 0; i < 3; ++i) half[f][i] = 0.5 * cot[(i + 2) % 3];  // halfedge i faces corner i+2
  }
  std::vector<std::array<double, 3>> weight(nf);
  for (int f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i) {
      const int t = mesh.twin[f][i];
      weight[f][i] = half[f][i] + (t >= 0 ? half[t / 3][t % 3] : 0.0);
    }
  return weight;
}

Eigen::SparseMatrix<double, Eigen::RowMajor> cotan_laplacian(const IntrinsicMesh& mesh) {
  const int nf = mesh.face_count();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(12 * static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    validate_face_lengths(mesh, f);
    const std::array<double, 3> cot = corner_cotangents(mesh.edge_lengths[f]);
    for (int i = 0; i < 3; ++i) {
      // Each face adds the half-weight of each of its halfedges; summing duplicates (setFromTriplets)
      // assembles the two sides of interior edges, parallel edges between the same two vertices,
      // and self-loops (whose four entries cancel, as w (u_a - u_a) = 0 requires).
      const double w = 0.5 * cot[(i + 2) % 3];
      const int a = mesh.faces[f][i], b = mesh.faces[f][(i + 1) % 3];
      triplets.emplace_back(a, a, w);
      triplets.emplace_back(b, b, w);
      triplets.emplace_back(a, b, -w);
      triplets.emplace_back(b, a, -w);
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> laplacian(mesh.vertex_count, mesh.vertex_count);
  laplacian.setFromTriplets(triplets.begin(), triplets.end());
  laplacian.makeCompressed();
  return laplacian;
}

std::vector<double> lumped_mass(const IntrinsicMesh& mesh) {
  std::vector<double> mass(static_cast<size_t>(mesh.vertex_count), 0.0);
  for (int f = 0; f < mesh.face_count(); ++f) {
    const double third = triangle_area_from_lengths(mesh.edge_lengths[f]) / 3.0;
    for (int k = 0; k < 3; ++k) mass[mesh.faces[f][k]] += third;
  }
  return mass;
}

Eigen::Vector2d face_gradient(const SurfaceDomain& domain, int face, const std::array<double, 3>& corner_values) {
  // grad b_k = rot90(c_{k+2} - c_{k+1}) / (2A): the inward normal of the opposite edge, scaled so b_k
  // rises from 0 on that edge to 1 at corner k.
  const std::array<Eigen::Vector2d, 3>& c = domain.face_corners[face];
  const double two_area = 2.0 * domain.face_area[face];
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d e = c[(k + 2) % 3] - c[(k + 1) % 3];
    g += corner_values[k] * Eigen::Vector2d(-e.y(), e.x());
  }
  return g / two_area;
}

std::vector<Eigen::Vector2d> face_gradients(const SurfaceDomain& domain, const std::vector<double>& vertex_values) {
  std::vector<Eigen::Vector2d> out(static_cast<size_t>(domain.face_count));
  for (int f = 0; f < domain.face_count; ++f) {
    const std::array<int, 3>& v = domain.face_vertices[f];
    out[f] = face_gradient(domain, f, {vertex_values[v[0]], vertex_values[v[1]], vertex_values[v[2]]});
  }
  return out;
}

}  // namespace physarum
