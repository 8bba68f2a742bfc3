#include "common/surface/intrinsic_point_location.hpp"

#include "common/base/errors.hpp"
#include "common/surface/chord_geometry.hpp"
#include "common/surface/field_transfer.hpp"

#include <cmath>
#include <string>

namespace physarum {
namespace {

Eigen::Vector3d normalised_nonnegative(const Eigen::Vector3d& beta) {
  const Eigen::Vector3d b = beta.cwiseMax(0.0);
  const double sum = b.sum();
  return sum > 0.0 ? Eigen::Vector3d(b / sum) : Eigen::Vector3d(1.0, 0.0, 0.0);
}

// The corner of input face `face` that `point` sits on, or -1 (barycentric 1 up to rounding).
int input_corner_at(const InputMesh& mesh, const SurfacePoint& point) {
  for (int k = 0; k < 3; ++k)
    if (point.barycentric[k] > 1.0 - 1e-12) return mesh.triangles[static_cast<size_t>(point.face)][k];
  return -1;
}

}  // namespace

IntrinsicPointLocator::IntrinsicPointLocator(const InputMesh& mesh, const SurfaceDomain& domain)
    : mesh_(mesh), chords_(chord_triangles(mesh, domain)), overlaps_(mesh, domain, chords_) {}

IntrinsicLocation IntrinsicPointLocator::locate(const SurfacePoint& point) const {
  if (point.face < 0 || point.face >= mesh_.triangle_count())
    throw InputError(mesh_.source + ": a surface point names face " + std::to_string(point.face) + ", which does not exist");
  const auto& corners = mesh_.triangles[static_cast<size_t>(point.face)];
  const Eigen::Vector3d x = point.barycentric[0] * mesh_.positions[corners[0]] +
                            point.barycentric[1] * mesh_.positions[corners[1]] +
                            point.barycentric[2] * mesh_.positions[corners[2]];
  // The containing chord triangle nearest to x (its distance, plus a penalty for lying just outside).
  IntrinsicLocation best;
  double best_score = HUGE_VAL, best_size = 0.0;
  for (const int T : overlaps_.of(point.face)) {
    const auto& c = chords_[static_cast<size_t>(T)].corner;
    const Chord chord(c[0], c[1], c[2]);
    if (chord.degenerate) continue;
    const Eigen::Vector3d beta = chord.barycentric(x);
    const double outside = -beta.minCoeff();
    if (outside > kChordSlack) continue;
    const double score = std::abs(chord.signed_distance(x)) + chord.longest_edge * std::max(0.0, outside);
    if (score < best_score) best_score = score, best_size = chord.longest_edge, best = {T, normalised_nonnegative(beta)};
  }
  if (best.face >= 0 && best_score <= kAcceptableDistance * best_size) return best;
  // None acceptable: the nearest chord triangle, at its nearest point.
  double nearest = HUGE_VAL;
  for (const int T : overlaps_.of(point.face)) {
    const auto& c = chords_[static_cast<size_t>(T)].corner;
    const auto [beta, distance2] = nearest_on_triangle(x, c[0], c[1], c[2], Chord(c[0], c[1], c[2]));
    if (distance2 < nearest) nearest = distance2, best = {T, normalised_nonnegative(beta)};
  }
  if (best.face < 0) throw InputError(mesh_.source + ": no intrinsic face covers input face " + std::to_string(point.face));
  return best;
}

Eigen::SparseMatrix<double, Eigen::RowMajor> interpolation_at_points(const InputMesh& mesh, const SurfaceDomain& domain,
                                                                     const std::vector<SurfacePoint>& points) {
  const InputVertexData<int> vertex_of_input = input_vertex_to_intrinsic(mesh, domain.vertex_location);
  const IntrinsicPointLocator locator(mesh, domain);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const int row = static_cast<int>(i);
    const int corner = input_corner_at(mesh, points[i]);
    if (corner >= 0) {
      entries.emplace_back(row, vertex_of_input[static_cast<size_t>(corner)], 1.0);
      continue;
    }
    const IntrinsicLocation at = locator.locate(points[i]);
    const auto& v = domain.face_vertices[static_cast<size_t>(at.face)];
    for (int k = 0; k < 3; ++k)
      if (at.barycentric[k] != 0.0) entries.emplace_back(row, v[static_cast<size_t>(k)], at.barycentric[k]);
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> P(static_cast<Eigen::Index>(points.size()), domain.vertex_count);
  P.setFromTriplets(entries.begin(), entries.end());  // repeated vertices (a loop edge) are summed
  return P;
}

}  // namespace physarum
