#include "common/surface/input_face_overlaps.hpp"

#include "common/base/errors.hpp"
#include "common/base/parallel_chunks.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace physarum {
namespace {

struct Box {
  Eigen::Vector3d low, high;
  bool meets(const Box& other) const {
    return (low.array() <= other.high.array()).all() && (other.low.array() <= high.array()).all();
  }
};

// Whether triangle a b c meets the box: the separating axis test (Akenine-Moeller 2001) over the box's
// three axes, the triangle's normal and the nine cross products of their edges. Exact up to
// rounding, which the caller's slack absorbs; much tighter than comparing bounding boxes for the
// tilted, large input faces around a small intrinsic face.
bool triangle_meets_box(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Box& box) {
  const Eigen::Vector3d centre = 0.5 * (box.low + box.high), half = 0.5 * (box.high - box.low);
  const std::array<Eigen::Vector3d, 3> v{a - centre, b - centre, c - centre};
  const std::array<Eigen::Vector3d, 3> edge{v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  auto separated_along = [&](const Eigen::Vector3d& axis) {
    const double p0 = v[0].dot(axis), p1 = v[1].dot(axis), p2 = v[2].dot(axis);
    const double radius = half.dot(axis.cwiseAbs());
    return std::min({p0, p1, p2}) > radius || std::max({p0, p1, p2}) < -radius;
  };
  for (int k = 0; k < 3; ++k)
    if (separated_along(Eigen::Vector3d::Unit(k))) return false;
  if (separated_along(edge[0].cross(edge[1]))) return false;
  for (const Eigen::Vector3d& e : edge)
    for (int k = 0; k < 3; ++k)
      if (separated_along(e.cross(Eigen::Vector3d::Unit(k)))) return false;
  return true;
}

// Input faces sharing an edge with each input face, as CSR lists.
struct FaceAdjacency {
  std::vector<size_t> first;
  std::vector<int> faces;
};

FaceAdjacency edge_adjacency(const InputMesh& mesh) {
  struct EdgeUse {
    int low, high, face;
  };
  std::vector<EdgeUse> uses;
  uses.reserve(static_cast<size_t>(mesh.triangle_count()) * 3);
  for (int f = 0; f < mesh.triangle_count(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.triangles[f][c], b = mesh.triangles[f][(c + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), f});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.low != y.low ? x.low < y.low : x.high != y.high ? x.high < y.high : x.face < y.face;
  });
  std::vector<std::pair<int, int>> links;  // (face, neighbour), both directions
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].low == uses[i].low && uses[j].high == uses[i].high) ++j;
    for (size_t a = i; a < j; ++a)
      for (size_t b = i; b < j; ++b)
        if (a != b && uses[a].face != uses[b].face) links.emplace_back(uses[a].face, uses[b].face);
    i = j;
  }
  FaceAdjacency adjacency;
  adjacency.first.assign(static_cast<size_t>(mesh.triangle_count()) + 1, 0);
  for (const auto& [face, neighbour] : links) ++adjacency.first[static_cast<size_t>(face) + 1];
  for (size_t f = 0; f + 1 < adjacency.first.size(); ++f) adjacency.first[f + 1] += adjacency.first[f];
  adjacency.faces.resize(links.size());
  std::vector<size_t> fill(adjacency.first.begin(), adjacency.first.end() - 1);
  for (const auto& [face, neighbour] : links) adjacency.faces[fill[static_cast<size_t>(face)]++] = neighbour;
  return adjacency;
}

double surface_area(const InputMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles)
    area += 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]).norm();
  return area;
}

}  // namespace

InputFaceOverlaps::InputFaceOverlaps(const InputMesh& mesh, const SurfaceDomain& domain,
                                     const std::vector<ChordTriangle>& chords) {
  if (static_cast<int>(chords.size()) != domain.face_count)
    throw InputError("overlaps of " + mesh.source + ": " + std::to_string(chords.size()) + " chord triangles for " +
                     std::to_string(domain.face_count) + " intrinsic faces");
  const double mesh_area = surface_area(mesh);
  length_scale_ = domain.total_area > 0.0 && mesh_area > 0.0 ? std::sqrt(mesh_area / domain.total_area) : 1.0;

  const FaceAdjacency adjacency = edge_adjacency(mesh);
  std::vector<Box> input_box(static_cast<size_t>(mesh.triangle_count()));
  Eigen::Vector3d everything_low = Eigen::Vector3d::Constant(0.0), everything_high = everything_low;
  for (int f = 0; f < mesh.triangle_count(); ++f) {
    const auto& t = mesh.triangles[f];
    Box& b = input_box[static_cast<size_t>(f)];
    b.low = mesh.positions[t[0]].cwiseMin(mesh.positions[t[1]]).cwiseMin(mesh.positions[t[2]]);
    b.high = mesh.positions[t[0]].cwiseMax(mesh.positions[t[1]]).cwiseMax(mesh.positions[t[2]]);
    everything_low = f == 0 ? b.low : everything_low.cwiseMin(b.low);
    everything_high = f == 0 ? b.high : everything_high.cwiseMax(b.high);
  }
  // Slack for rounding in the lengths and locations: relative, plus a tiny absolute part so that a
  // face of zero size still meets the faces it touches.
  const double absolute_slack = 1e-9 * (everything_high - everything_low).norm();

  // Flood fill per intrinsic face, in chunks of faces that each collect their own (input, intrinsic)
  // pairs; chunks are concatenated in order, so every list comes out sorted.
  const int face_count = domain.face_count;
  const int chunk_count = std::max(1, std::min(64, face_count / 4096 + 1));
  std::vector<std::vector<std::pair<int, int>>> chunk_pairs(static_cast<size_t>(chunk_count));
  parallel_chunks(chunk_count, [&](int chunk) {
    const int begin = static_cast<int>(static_cast<long long>(face_count) * chunk / chunk_count);
    const int end = static_cast<int>(static_cast<long long>(face_count) * (chunk + 1) / chunk_count);
    std::vector<int> stamp(static_cast<size_t>(mesh.triangle_count()), -1);  // last intrinsic face that visited
    std::vector<int> queue;
    auto& pairs = chunk_pairs[static_cast<size_t>(chunk)];
    pairs.reserve(static_cast<size_t>(end - begin) * 2);
    for (int face = begin; face < end; ++face) {
      const auto& corners = domain.face_corners[static_cast<size_t>(face)];
      const ChordTriangle& chord = chords[static_cast<size_t>(face)];
      Box box{Eigen::Vector3d::Constant(-HUGE_VAL), Eigen::Vector3d::Constant(HUGE_VAL)};
      for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        const Eigen::Vector3d& p = chord.corner[i];
        // Surface distance bound from corner i: its two edges (never less than the chords, so
        // that rounding in the traced locations cannot shrink the box below its own corners).
        const double to_j = std::max((corners[j] - corners[i]).norm() * length_scale_,
                                     (chord.corner[j] - p).norm());
        const double to_k = std::max((corners[k] - corners[i]).norm() * length_scale_,
                                     (chord.corner[k] - p).norm());
        const double radius = std::max(to_j, to_k) * (1.0 + 1e-9) + absolute_slack;
        box.low = box.low.cwiseMax(p - Eigen::Vector3d::Constant(radius));
        box.high = box.high.cwiseMin(p + Eigen::Vector3d::Constant(radius));
      }
      queue.clear();
      for (int i = 0; i < 3; ++i) {
        const int start = chord.input_face[i];
        if (start < 0 || start >= mesh.triangle_count())
          throw InputError("overlaps of " + mesh.source + ": intrinsic face " + std::to_string(face) +
                           " has a corner on input face " + std::to_string(start) + ", which the mesh does not have");
        if (stamp[static_cast<size_t>(start)] == face) continue;
        stamp[static_cast<size_t>(start)] = face;
        queue.push_back(start);  // holds a vertex of the face: overlaps it whatever its box says
      }
      for (size_t q = 0; q < queue.size(); ++q) {
        const int f = queue[q];
        pairs.emplace_back(f, face);
        for (size_t a = adjacency.first[static_cast<size_t>(f)]; a < adjacency.first[static_cast<size_t>(f) + 1]; ++a) {
          const int g = adjacency.faces[a];
          if (stamp[static_cast<size_t>(g)] == face) continue;
          stamp[static_cast<size_t>(g)] = face;
          if (!input_box[static_cast<size_t>(g)].meets(box)) continue;
          const auto& t = mesh.triangles[static_cast<size_t>(g)];
          if (triangle_meets_box(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], box))
            queue.push_back(g);
        }
      }
    }
  });

  first_.assign(static_cast<size_t>(mesh.triangle_count()) + 1, 0);
  for (const auto& pairs : chunk_pairs)
    for (const auto& [input_face, intrinsic_face] : pairs) ++first_[static_cast<size_t>(input_face) + 1];
  for (size_t f = 0; f + 1 < first_.size(); ++f) first_[f + 1] += first_[f];
  faces_.resize(first_.back());
  std::vector<size_t> fill(first_.begin(), first_.end() - 1);
  for (const auto& pairs : chunk_pairs)
    for (const auto& [input_face, intrinsic_face] : pairs) faces_[fill[static_cast<size_t>(input_face)]++] = intrinsic_face;
}

}  // namespace physarum
