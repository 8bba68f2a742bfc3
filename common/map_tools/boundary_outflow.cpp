#include "common/map_tools/boundary_outflow.hpp"

#include <algorithm>

namespace physarum {
namespace {

// Rotations compose by adding angles: (a then b) as complex numbers, b * a.
Rotation2 then(const Rotation2& a, const Rotation2& b) {
  return {b.cos_angle * a.cos_angle - b.sin_angle * a.sin_angle, b.sin_angle * a.cos_angle + b.cos_angle * a.sin_angle};
}

Eigen::Vector2d undo(const Rotation2& r, const Eigen::Vector2d& d) { return Rotation2{r.cos_angle, -r.sin_angle}.apply_direction(d); }

int corner_of(const SurfaceDomain& d, int face, int vertex) {
  const auto& v = d.face_vertices[static_cast<size_t>(face)];
  return v[0] == vertex ? 0 : v[1] == vertex ? 1 : 2;
}

// The outward normals of the boundary edges at corner k of `face`, carried into that face's frame:
// the fan around the corner's vertex is walked both ways (across edge k, which leaves the vertex,
// and across the edge that arrives at it) until a boundary edge ends it. A closed fan (an interior
// vertex) adds nothing. Each edge's normal is the edge's perpendicular pointing away from its face.
Eigen::Vector2d outward_normal_at(const SurfaceDomain& d, int face, int k) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  const int vertex = d.face_vertices[static_cast<size_t>(face)][k];
  for (const bool leaving : {true, false}) {
    int g = face, corner = k;
    Rotation2 into_g;  // face's frame -> g's frame
    for (int step = 0; step < 1024; ++step) {
      const int edge = leaving ? corner : (corner + 2) % 3;
      const int next = d.face_neighbour[static_cast<size_t>(g)][edge];
      if (next < 0) {
        const auto& p = d.face_corners[static_cast<size_t>(g)];
        const Eigen::Vector2d e = p[(edge + 1) % 3] - p[edge];
        Eigen::Vector2d normal(e.y(), -e.x());
        if (normal.dot(p[(edge + 2) % 3] - p[edge]) > 0.0) normal = -normal;
        sum += undo(into_g, normal.normalized());
        break;
      }
      into_g = then(into_g, d.edge_transition[static_cast<size_t>(3 * g + edge)]);
      g = next;
      if (g == face) break;  // around an interior vertex
      corner = corner_of(d, g, vertex);
    }
  }
  return sum;
}

}  // namespace

std::vector<FaceDirectionOverride> outflow_directions(const SurfaceDomain& domain, const std::vector<char>& on_boundary,
                                                      const std::vector<char>& keep, const FaceDirection& field) {
  auto touches = [&](int face, const std::vector<char>& flag) {
    const auto& v = domain.face_vertices[static_cast<size_t>(face)];
    return flag[static_cast<size_t>(v[0])] || flag[static_cast<size_t>(v[1])] || flag[static_cast<size_t>(v[2])];
  };
  constexpr int kMaxSteps = 4;
  std::vector<FaceDirectionOverride> out;
  std::vector<int> visited_at(static_cast<size_t>(domain.face_count), -1);  // the face a search last reached it from
  struct Reached {
    int face;
    Rotation2 into;  // the start face's frame -> this face's frame
  };
  std::vector<Reached> front, next;
  for (int face = 0; face < domain.face_count; ++face) {
    if (!touches(face, on_boundary) || touches(face, keep)) continue;
    // Breadth first across interior edges, to the first ring of faces clear of the boundary.
    Eigen::Vector2d interior = Eigen::Vector2d::Zero();
    bool found = false;
    front.assign(1, Reached{face, Rotation2{}});
    visited_at[static_cast<size_t>(face)] = face;
    for (int step = 0; step < kMaxSteps && !found && !front.empty(); ++step) {
      next.clear();
      for (const Reached& r : front)
        for (int e = 0; e < 3; ++e) {
          const int g = domain.face_neighbour[static_cast<size_t>(r.face)][e];
          if (g < 0 || visited_at[static_cast<size_t>(g)] == face) continue;
          visited_at[static_cast<size_t>(g)] = face;
          next.push_back({g, then(r.into, domain.edge_transition[static_cast<size_t>(3 * r.face + e)])});
        }
      for (const Reached& r : next) {
        if (touches(r.face, on_boundary)) continue;
        if (const std::optional<Eigen::Vector2d> x = field(r.face)) {
          interior += undo(r.into, *x);
          found = true;
        }
      }
      front.swap(next);
    }
    if (!found || !(interior.norm() > 0.0)) continue;
    Eigen::Vector2d outward = Eigen::Vector2d::Zero();
    for (int k = 0; k < 3; ++k)
      if (on_boundary[static_cast<size_t>(domain.face_vertices[static_cast<size_t>(face)][k])])
        outward += outward_normal_at(domain, face, k);
    if (interior.dot(outward) > 0.0) out.push_back({face, interior.normalized()});
  }
  return out;
}

}  // namespace physarum
