#include "common/mesh/closest_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace physarum {

Eigen::Vector3d closest_point_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {1.0 - v, v, 0.0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {1.0 - w, 0.0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - w, w};
  }
  const double denominator = va + vb + vc;
  if (!(std::abs(denominator) > 0.0)) return {1.0, 0.0, 0.0};  // a degenerate triangle: its first corner
  const double v = vb / denominator, w = vc / denominator;
  return {1.0 - v - w, v, w};
}

namespace {

// Cells per axis are kept below this so that a key packs three of them into 63 bits.
constexpr std::int64_t kCellsPerAxis = 1 << 20;

}  // namespace

FaceLocator::FaceLocator(const InputMesh& mesh) : mesh_(mesh) {
  all_faces_.resize(mesh.triangles.size());
  std::iota(all_faces_.begin(), all_faces_.end(), 0);
  if (mesh.positions.empty() || mesh.triangles.empty()) return;
  Eigen::Vector3d low = mesh.positions.front(), high = low;
  for (const Eigen::Vector3d& p : mesh.positions) low = low.cwiseMin(p), high = high.cwiseMax(p);
  // About two faces across a cell: the mean edge length.
  double edges = 0.0;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      edges += (mesh.positions[static_cast<size_t>(t[static_cast<size_t>(k)])] -
                mesh.positions[static_cast<size_t>(t[static_cast<size_t>((k + 1) % 3)])]).norm();
  const double extent = (high - low).maxCoeff();
  cell_ = std::max({edges / (3.0 * static_cast<double>(mesh.triangles.size())), extent / (kCellsPerAxis - 2),
                    std::numeric_limits<double>::min()});
  origin_ = low - Eigen::Vector3d::Constant(cell_);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    Eigen::Vector3d a = mesh.positions[static_cast<size_t>(t[0])], b = a;
    for (int k = 1; k < 3; ++k) {
      a = a.cwiseMin(mesh.positions[static_cast<size_t>(t[static_cast<size_t>(k)])]);
      b = b.cwiseMax(mesh.positions[static_cast<size_t>(t[static_cast<size_t>(k)])]);
    }
    const Eigen::Array3i lo = ((a - origin_) / cell_).array().floor().cast<int>();
    const Eigen::Array3i hi = ((b - origin_) / cell_).array().floor().cast<int>();
    for (int z = lo.z(); z <= hi.z(); ++z)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int x = lo.x(); x <= hi.x(); ++x)
          cells_[(static_cast<std::int64_t>(z) * kCellsPerAxis + y) * kCellsPerAxis + x].push_back(static_cast<int>(f));
  }
}

std::int64_t FaceLocator::cell_key(const Eigen::Vector3d& p) const {
  const Eigen::Array3d c = ((p - origin_) / cell_).array().floor();
  if ((c < 0.0).any() || (c >= static_cast<double>(kCellsPerAxis)).any()) return -1;
  return (static_cast<std::int64_t>(c.z()) * kCellsPerAxis + static_cast<std::int64_t>(c.y())) * kCellsPerAxis +
         static_cast<std::int64_t>(c.x());
}

void FaceLocator::closest_of(const std::vector<int>& faces, const Eigen::Vector3d& p, SurfacePoint& found, double& best) const {
  for (const int f : faces) {
    const auto& t = mesh_.triangles[static_cast<size_t>(f)];
    const Eigen::Vector3d& a = mesh_.positions[static_cast<size_t>(t[0])];
    const Eigen::Vector3d& b = mesh_.positions[static_cast<size_t>(t[1])];
    const Eigen::Vector3d& c = mesh_.positions[static_cast<size_t>(t[2])];
    const Eigen::Vector3d bary = closest_point_barycentric(p, a, b, c);
    const double d = (bary[0] * a + bary[1] * b + bary[2] * c - p).squaredNorm();
    if (d < best) best = d, found = SurfacePoint{f, bary};
  }
}

SurfacePoint FaceLocator::locate(const Eigen::Vector3d& p) const {
  SurfacePoint found;
  double best = std::numeric_limits<double>::infinity();
  if (const auto cell = cells_.find(cell_key(p)); cell != cells_.end()) closest_of(cell->second, p, found, best);
  if (found.face < 0) closest_of(all_faces_, p, found, best);
  return found;
}

}  // namespace physarum
