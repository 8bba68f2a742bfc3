#include "common/fast_marching.hpp"

#include "common/errors.hpp"
#include "common/surface_pieces.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <string>
#include <utility>

namespace physarum {
namespace {

using Vec2 = Eigen::Vector2d;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The inverse of `rotation` applied to `v`.
Vec2 rotate_back(const Rotation2& rotation, const Vec2& v) {
  return {rotation.cos_angle * v.x() + rotation.sin_angle * v.y(), -rotation.sin_angle * v.x() + rotation.cos_angle * v.y()};
}

// The distance at C through triangle (A, B, C) from the distances at A and B (see the header): the
// virtual source S with |SA| = dA, |SB| = dB on the far side of AB from C; |SC| when the segment SC
// crosses AB, +infinity when it does not or when no such S exists (|dA - dB| > |AB| or dA + dB < |AB|).
// `source` receives S - C.
double two_point_update(const Vec2& pa, const Vec2& pb, const Vec2& pc, double da, double db, Vec2& source) {
  const Vec2 e = pb - pa;
  const double c = e.norm();
  if (!(c > 0.0)) return kInfinity;
  const Vec2 ex = e / c, ey(-ex.y(), ex.x());
  const Vec2 rc = pc - pa;
  const double cx = rc.dot(ex), cy = rc.dot(ey);
  if (cy == 0.0) return kInfinity;
  const double sx = (da * da - db * db + c * c) / (2.0 * c);
  const double s2 = da * da - sx * sx;
  // A hair below zero is rounding of a source on the line AB (dA + dB = |AB|).
  if (s2 < -1e-12 * c * c) return kInfinity;
  const double sy = (cy > 0.0 ? -1.0 : 1.0) * std::sqrt(std::max(s2, 0.0));
  // Where the segment from S to C meets the line through A and B.
  const double x = sy == 0.0 ? sx : sx + (cx - sx) * (-sy / (cy - sy));
  const double tolerance = 1e-12 * c;
  if (x < -tolerance || x > c + tolerance) return kInfinity;
  source = pa + sx * ex + sy * ey - pc;
  return std::hypot(cx - sx, cy - sy);
}

}  // namespace

FastMarchingGeodesics::FastMarchingGeodesics(const SurfaceDomain& domain) : domain_(domain), fans_(domain) {
  const int n = domain.vertex_count, faces = domain.face_count;
  vertex_face_start_.assign(static_cast<size_t>(n) + 1, 0);
  for (const auto& f : domain.face_vertices)
    for (const int v : f) ++vertex_face_start_[static_cast<size_t>(v) + 1];
  for (int v = 0; v < n; ++v) vertex_face_start_[static_cast<size_t>(v) + 1] += vertex_face_start_[static_cast<size_t>(v)];
  vertex_faces_.resize(static_cast<size_t>(3 * faces));
  {
    std::vector<int> next(vertex_face_start_.begin(), vertex_face_start_.end() - 1);
    for (int f = 0; f < faces; ++f)
      for (int k = 0; k < 3; ++k) vertex_faces_[static_cast<size_t>(next[static_cast<size_t>(domain.face_vertices[f][k])]++)] = 3 * f + k;
  }

  corner_split_.assign(static_cast<size_t>(3 * faces), 0);
  for (int f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      const auto& p = domain.face_corners[f];
      if ((p[(k + 1) % 3] - p[k]).dot(p[(k + 2) % 3] - p[k]) < 0.0) {
        ++obtuse_corners_;
        split_obtuse_corner(f, k);
      }
    }

  stencil_start_.assign(static_cast<size_t>(n) + 1, 0);
  for (const VirtualStencil& s : stencils_) ++stencil_start_[static_cast<size_t>(s.a) + 1], ++stencil_start_[static_cast<size_t>(s.b) + 1];
  for (int v = 0; v < n; ++v) stencil_start_[static_cast<size_t>(v) + 1] += stencil_start_[static_cast<size_t>(v)];
  stencils_by_base_.resize(2 * stencils_.size());
  std::vector<int> next(stencil_start_.begin(), stencil_start_.end() - 1);
  for (size_t i = 0; i < stencils_.size(); ++i) {
    stencils_by_base_[static_cast<size_t>(next[static_cast<size_t>(stencils_[i].a)]++)] = static_cast<int>(i);
    stencils_by_base_[static_cast<size_t>(next[static_cast<size_t>(stencils_[i].b)]++)] = static_cast<int>(i);
  }
}

void FastMarchingGeodesics::split_obtuse_corner(int face, int corner) {
  const SurfaceDomain& d = domain_;
  // The plane of `face`, C at the origin; corners C, A, B counter-clockwise.
  const int k = corner;
  const Vec2 origin = d.face_corners[face][k];
  const Vec2 a = d.face_corners[face][(k + 1) % 3] - origin, b = d.face_corners[face][(k + 2) % 3] - origin;
  const int target = d.face_vertices[face][k];
  const int vertex_a = d.face_vertices[face][(k + 1) % 3], vertex_b = d.face_vertices[face][(k + 2) % 3];
  // The edge being crossed: halfedge `edge` of `current` runs from P (the A side of the section)
  // to Q (the B side); the whole section passes through it.
  int current = face, edge = (k + 1) % 3;
  Vec2 p = a, q = b;
  for (int step = 0; step < kMaxUnfoldings; ++step) {
    const int next = d.face_neighbour[current][edge];
    if (next < 0) return;  // the strip ran into the boundary
    const int j = d.neighbour_edge[current][edge];
    // In `next`, halfedge j runs from Q to P and the third corner V lies on its left.
    const auto& corners = d.face_corners[next];
    const Vec2 along_g = corners[(j + 1) % 3] - corners[j];
    const double length_g = along_g.norm();
    if (!(length_g > 0.0)) return;
    const Vec2 local = corners[(j + 2) % 3] - corners[j];
    const double along = local.dot(along_g) / length_g, across = cross(along_g, local) / length_g;
    const Vec2 ex = (p - q).normalized(), ey(-ex.y(), ex.x());
    const Vec2 v = q + along * ex + across * ey;
    const int vertex_v = d.face_vertices[next][(j + 2) % 3];
    const bool beyond_a = v.dot(a) < 0.0, beyond_b = v.dot(b) < 0.0;
    if (!beyond_a && !beyond_b) {
      // In the section: the two virtual triangles are acute at C.
      if (vertex_v == target || vertex_v == vertex_a || vertex_v == vertex_b) return;
      stencils_.push_back({target, 3 * face + k, vertex_a, vertex_v, a, v});
      stencils_.push_back({target, 3 * face + k, vertex_v, vertex_b, v, b});
      corner_split_[static_cast<size_t>(3 * face + k)] = 1;
      ++split_corners_;
      return;
    }
    if (beyond_a && beyond_b) return;  // cannot happen in a valid layout; give up rather than guess
    current = next;
    if (beyond_a) {
      // V is past the perpendicular to CA, on the B side: the section leaves through PV.
      edge = (j + 1) % 3;
      q = v;
    } else {
      edge = (j + 2) % 3;
      p = v;
    }
  }
}

IntrinsicVertexData<double> FastMarchingGeodesics::distance(const std::vector<int>& seeds) const {
  const SurfaceDomain& d = domain_;
  const int n = d.vertex_count;
  if (seeds.empty()) throw InputError("fast marching: the seed set is empty");
  IntrinsicVertexData<double> dist(static_cast<size_t>(n), kInfinity);
  std::vector<char> accepted(static_cast<size_t>(n), 0);
  // Where each vertex's current distance comes from: the corner 3f + k it was reached through, and
  // the source S - C in that face's frame with the distance already travelled before S (see the header).
  std::vector<int> reach_corner(static_cast<size_t>(n), -1);
  std::vector<Vec2> reach_source(static_cast<size_t>(n), Vec2::Zero());
  std::vector<double> reach_offset(static_cast<size_t>(n), 0.0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  for (const int s : seeds) {
    if (s < 0 || s >= n)
      throw InputError("fast marching: seed " + std::to_string(s) + " is no intrinsic vertex (0.." + std::to_string(n - 1) + ")");
    dist[static_cast<size_t>(s)] = 0.0;
    heap.emplace(0.0, s);
  }
  auto offer = [&](int vertex, double value, int corner, const Vec2& source, double offset) {
    const auto v = static_cast<size_t>(vertex);
    if (value < dist[v]) {
      dist[v] = value;
      reach_corner[v] = corner;
      reach_source[v] = source;
      reach_offset[v] = offset;
      heap.emplace(value, vertex);
    }
  };
  while (!heap.empty()) {
    const auto [value, v] = heap.top();
    heap.pop();
    if (accepted[static_cast<size_t>(v)] || value > dist[static_cast<size_t>(v)]) continue;
    accepted[static_cast<size_t>(v)] = 1;
    const TrackedSource tracked = track_source(reach_corner[static_cast<size_t>(v)], reach_source[static_cast<size_t>(v)],
                                               reach_offset[static_cast<size_t>(v)]);
    for (int i = vertex_face_start_[static_cast<size_t>(v)]; i < vertex_face_start_[static_cast<size_t>(v) + 1]; ++i) {
      const int f = vertex_faces_[static_cast<size_t>(i)] / 3, k = vertex_faces_[static_cast<size_t>(i)] % 3;
      const auto& p = d.face_corners[f];
      const auto& corner_vertex = d.face_vertices[f];
      for (int m = 1; m <= 2; ++m) {
        const int c = (k + m) % 3, o = (k + 3 - m) % 3;  // target corner c, the third corner o
        const int target = corner_vertex[c], other = corner_vertex[o];
        if (accepted[static_cast<size_t>(target)]) continue;
        const int target_corner = 3 * f + c;
        Vec2 source = p[k] - p[c];
        double candidate = value + source.norm(), offset = value;
        Vec2 two_point_source = Vec2::Zero();
        if (!corner_split_[static_cast<size_t>(target_corner)] && accepted[static_cast<size_t>(other)]) {
          const double through = two_point_update(p[k], p[o], p[c], value, dist[static_cast<size_t>(other)], two_point_source);
          if (through < candidate) {
            candidate = through;
            source = two_point_source;
            offset = 0.0;
          }
        }
        Vec2 unfolded_source = Vec2::Zero();
        const double along = tracked_update(tracked, f, k, c, unfolded_source);
        if (along < candidate) {
          candidate = along;
          source = unfolded_source;
          offset = tracked.offset;
        }
        offer(target, candidate, target_corner, source, offset);
      }
    }
    for (int i = stencil_start_[static_cast<size_t>(v)]; i < stencil_start_[static_cast<size_t>(v) + 1]; ++i) {
      const VirtualStencil& s = stencils_[static_cast<size_t>(stencils_by_base_[static_cast<size_t>(i)])];
      if (accepted[static_cast<size_t>(s.target)]) continue;
      const int other = s.a == v ? s.b : s.a;
      if (!accepted[static_cast<size_t>(other)]) continue;
      Vec2 source = Vec2::Zero();
      const double through = two_point_update(s.position_a, s.position_b, Vec2::Zero(), dist[static_cast<size_t>(s.a)],
                                              dist[static_cast<size_t>(s.b)], source);
      offer(s.target, through, s.target_corner, source, 0.0);
    }
  }
  for (int v = 0; v < n; ++v)
    if (!accepted[static_cast<size_t>(v)]) {
      require_seed_in_every_piece(surface_pieces(d), seeds, "fast marching");
      throw InputError("fast marching: intrinsic vertex " + std::to_string(v) + " was never reached from the seeds");
    }
  return dist;
}

FastMarchingGeodesics::TrackedSource FastMarchingGeodesics::track_source(int corner, const Vec2& source, double offset) const {
  TrackedSource tracked;
  const double length = source.norm();
  if (corner < 0 || !(length > 0.0)) return tracked;  // a seed: nothing to unfold
  const VertexFans::Corner& at = fans_.corner(corner);
  const auto& p = domain_.face_corners[corner / 3];
  const int k = corner % 3;
  const Vec2 edge = p[(k + 1) % 3] - p[k];
  // The source lies in the corner's own sector (every update's segment crosses the opposite edge or
  // runs along a side); clamping only removes rounding.
  const double inside = std::clamp(std::atan2(cross(edge, source), edge.dot(source)), 0.0, at.angle);
  tracked.fan = at.fan;
  tracked.direction = at.start + inside;
  tracked.in_fan = at.to_fan.apply_direction(source);
  tracked.offset = offset;
  return tracked;
}

double FastMarchingGeodesics::tracked_update(const TrackedSource& tracked, int face, int corner, int target_corner,
                                             Vec2& source) const {
  const VertexFans::Corner& at = fans_.corner(3 * face + corner);
  if (tracked.fan < 0 || at.fan != tracked.fan) return kInfinity;
  const VertexFans::Fan& fan = fans_.fan(at.fan);
  // Angle of the source from the corner's edge to corner k+1, going round the fan the way that
  // enters the face through the edge to the other corner: counter-clockwise of the face when the
  // target is corner k+1 (at angle 0, the entry edge at `angle`), clockwise when it is corner k+2.
  const bool target_is_next = target_corner == (corner + 1) % 3;
  double angle = tracked.direction - at.start;
  Vec2 in_fan = tracked.in_fan;
  if (fan.closed) {
    if (target_is_next && angle < at.angle) {
      angle += fan.cone_angle;
      in_fan = fan.turn.apply_direction(in_fan);
    } else if (!target_is_next && angle > 0.0) {
      angle -= fan.cone_angle;
      in_fan = rotate_back(fan.turn, in_fan);
    }
  }
  // The segment from S to the target passes the vertex on the entry edge's side within half a turn.
  if (target_is_next ? !(angle > at.angle && angle < at.angle + std::numbers::pi) : !(angle < 0.0 && angle > at.angle - std::numbers::pi))
    return kInfinity;
  const auto& p = domain_.face_corners[face];
  const Vec2& vertex = p[corner];
  const Vec2& target = p[target_corner];
  const Vec2& entry = p[3 - corner - target_corner];
  const Vec2 unfolded = vertex + rotate_back(at.to_fan, in_fan);
  // A real unfolded path only when the segment crosses the entry edge between its ends.
  const double side_vertex = cross(target - unfolded, vertex - unfolded), side_entry = cross(target - unfolded, entry - unfolded);
  if (side_vertex * side_entry > 0.0) return kInfinity;
  source = unfolded - target;
  return tracked.offset + source.norm();
}

}  // namespace physarum
