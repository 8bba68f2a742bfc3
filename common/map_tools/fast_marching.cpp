#include "common/map_tools/fast_marching.hpp"

#include "common/base/errors.hpp"
#include "common/surface/surface_pieces.hpp"

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
// Relative size of rounding in lengths and in the orientation tests below: a source lying on an
// edge's line (every source one edge away from a seed does) must not fall off it by rounding.
constexpr double kRounding = 1e-12;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
double square(double x) { return x * x; }

// x <= kRounding * sqrt(scale_squared): zero up to rounding or below (no square root on the way).
bool within_rounding(double x, double scale_squared) { return x <= 0.0 || x * x <= kRounding * kRounding * scale_squared; }

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


// Calls visit(target vertex, its corner 3g + c, S' - target) for every face g around an accepted
// vertex V that a straight line from V's source S enters across an edge at V: S' is S unfolded into
// g by walking round V from the face V was reached through (`corner`, `source` = S - V in its
// frame), counter-clockwise (the line then enters g through its edge to corner k+1 and ends at
// corner k+2) and clockwise (the mirror image).
//
// The walk unfolds V's faces exactly; where the segment S'T passes outside them, beyond the far end
// W of an edge walked over, it stands for a path on the far side of W, which is as long as the
// segment only when W is flat, and not much shorter when W is convex (a cone angle below 2 pi: no
// shortest path goes through it). Past a saddle vertex (more than 2 pi) or a boundary vertex it
// would be a shortcut that does not exist, so such an edge must be crossed between V and W: the
// rays from S' that do form a window between the ray through V and the ray through the tightest
// such W, and a target counts when it is inside. The edge the line enters g through is always held
// to that (the line has to enter g). The walk stops once the source is more than half a turn round
// from the edge crossed: the line to any target further round passes on the other side of V.
template <class Visit>
void unfold_source_around_vertex(const SurfaceDomain& d, const std::vector<char>& blocking, int corner, const Vec2& source,
                                 Visit&& visit) {
  if (corner < 0) return;  // a seed: it is its own source
  for (const bool counter_clockwise : {true, false}) {
    int f = corner / 3, k = corner % 3;
    Vec2 s = source;          // S' - V in the frame of f
    Vec2 tightest(0.0, 0.0);  // blocking end bounding the window, minus V
    bool bounded = false;
    while (true) {
      const int edge = counter_clockwise ? (k + 2) % 3 : k;  // halfedges of f at V: k leaves V, k+2 arrives
      const int g = d.face_neighbour[f][edge];
      if (g < 0) break;
      const int j = d.neighbour_edge[f][edge];
      const Rotation2& into_g = d.edge_transition[static_cast<size_t>(3 * f + edge)];
      s = into_g.apply_direction(s);
      tightest = into_g.apply_direction(tightest);
      f = g;
      k = counter_clockwise ? j : (j + 1) % 3;
      if (3 * f + k == corner) break;  // all the way round
      const auto& p = d.face_corners[f];
      const int entry_corner = counter_clockwise ? (k + 1) % 3 : (k + 2) % 3, target_corner = 3 - k - entry_corner;
      const Vec2 entry = p[entry_corner] - p[k];
      const double side = cross(entry, s);
      if (!within_rounding(counter_clockwise ? side : -side, entry.squaredNorm() * s.squaredNorm())) break;
      // The entry edge's end bounds the window for this target; it narrows it for good when blocking
      // and tighter than the bound so far (on V's side of the ray from S' through it).
      const Vec2 to_tightest = tightest - s, to_entry = entry - s;
      const bool tighter = !bounded || within_rounding(-cross(to_tightest, to_entry) * cross(to_tightest, -s),
                                                       square(to_tightest.squaredNorm()) * to_entry.squaredNorm() * s.squaredNorm());
      const Vec2 bound = tighter ? entry : tightest;
      if (tighter && blocking[static_cast<size_t>(d.face_vertices[f][entry_corner])]) {
        tightest = entry;
        bounded = true;
      }
      // Inside the window: V and the bound on either side of the line from S' to the target (or on it).
      const Vec2 to_target = p[target_corner] - p[k] - s, to_bound = bound - s;
      if (within_rounding(cross(to_target, -s) * cross(to_target, to_bound),
                          square(to_target.squaredNorm()) * s.squaredNorm() * to_bound.squaredNorm()))
        visit(d.face_vertices[f][target_corner], 3 * f + target_corner, Vec2(-to_target));
    }
  }
}

}  // namespace

FastMarchingGeodesics::FastMarchingGeodesics(const SurfaceDomain& domain) : domain_(domain) {
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

  // Saddle and boundary vertices: straight lines may not pass them on the far side (see
  // unfold_source_around_vertex). Flat vertices sum to 2 pi up to rounding; the margin keeps them out.
  std::vector<double> angle_sum(static_cast<size_t>(n), 0.0);
  blocking_.assign(static_cast<size_t>(n), 0);
  for (int f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      const auto& p = domain.face_corners[f];
      const Vec2 to_next = p[(k + 1) % 3] - p[k], to_previous = p[(k + 2) % 3] - p[k];
      const auto v = static_cast<size_t>(domain.face_vertices[f][k]);
      angle_sum[v] += std::atan2(cross(to_next, to_previous), to_next.dot(to_previous));
      if (domain.face_neighbour[f][k] < 0 || domain.face_neighbour[f][(k + 2) % 3] < 0) blocking_[v] = 1;
    }
  for (int v = 0; v < n; ++v)
    if (angle_sum[static_cast<size_t>(v)] > 2.0 * std::numbers::pi + 1e-9) blocking_[static_cast<size_t>(v)] = 1;

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
  // Each vertex keeps two tentative values (see the header): the shortest path found (edge and
  // tracked-source updates) and the shortest virtual-source estimate (two-point updates). Its
  // distance is the path once a tracked source has reached it, else the smaller of the two.
  std::vector<Reach> path(static_cast<size_t>(n)), estimate(static_cast<size_t>(n));
  std::vector<char> tracked_reached(static_cast<size_t>(n), 0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  for (const int s : seeds) {
    if (s < 0 || s >= n)
      throw InputError("fast marching: seed " + std::to_string(s) + " is no intrinsic vertex (0.." + std::to_string(n - 1) + ")");
    dist[static_cast<size_t>(s)] = 0.0;
    path[static_cast<size_t>(s)].value = 0.0;
    tracked_reached[static_cast<size_t>(s)] = 1;
    heap.emplace(0.0, s);
  }
  // One call per update, so the heap gets at most one entry for it.
  auto offer = [&](int vertex, const Reach& path_candidate, bool is_tracked, const Reach& estimate_candidate) {
    const auto v = static_cast<size_t>(vertex);
    if (path_candidate.value < path[v].value) path[v] = path_candidate;
    if (estimate_candidate.value < estimate[v].value) estimate[v] = estimate_candidate;
    tracked_reached[v] |= static_cast<char>(is_tracked);
    const double key = tracked_reached[v] ? path[v].value : std::min(path[v].value, estimate[v].value);
    if (key != dist[v]) {
      dist[v] = key;
      heap.emplace(key, vertex);
    }
  };
  while (!heap.empty()) {
    const auto [value, v] = heap.top();
    heap.pop();
    // Entries left behind when a value changed (it may also rise, when a tracked path replaces an estimate).
    if (accepted[static_cast<size_t>(v)] || value != dist[static_cast<size_t>(v)]) continue;
    accepted[static_cast<size_t>(v)] = 1;
    // Only a path's source is unfolded: an estimate's virtual source is no point any path starts
    // from, and lines drawn from it in other directions than the one it was fitted to can be
    // shorter than any path on the surface. A path that an estimate beats only by rounding (on a
    // flat surface both are the same line) still counts.
    const Reach& reach = path[static_cast<size_t>(v)];
    if (reach.value - value <= kRounding * value)
      unfold_source_around_vertex(d, blocking_, reach.corner, reach.source, [&](int target, int target_corner, const Vec2& source) {
        if (!accepted[static_cast<size_t>(target)])
          offer(target, Reach{reach.offset + source.norm(), target_corner, source, reach.offset}, true, Reach{});
      });
    for (int i = vertex_face_start_[static_cast<size_t>(v)]; i < vertex_face_start_[static_cast<size_t>(v) + 1]; ++i) {
      const int f = vertex_faces_[static_cast<size_t>(i)] / 3, k = vertex_faces_[static_cast<size_t>(i)] % 3;
      const auto& p = d.face_corners[f];
      const auto& corner_vertex = d.face_vertices[f];
      for (int m = 1; m <= 2; ++m) {
        const int c = (k + m) % 3, o = (k + 3 - m) % 3;  // target corner c, the third corner o
        const int target = corner_vertex[c], other = corner_vertex[o];
        if (accepted[static_cast<size_t>(target)]) continue;
        const int target_corner = 3 * f + c;
        // Along the edge: a path that bends at this vertex.
        const Reach along_edge{value + (p[k] - p[c]).norm(), target_corner, p[k] - p[c], value};
        // An estimate matters only until a tracked source reaches the target.
        Reach estimate_candidate;
        if (!tracked_reached[static_cast<size_t>(target)] && !corner_split_[static_cast<size_t>(target_corner)] &&
            accepted[static_cast<size_t>(other)]) {
          estimate_candidate.corner = target_corner;
          estimate_candidate.value =
              two_point_update(p[k], p[o], p[c], value, dist[static_cast<size_t>(other)], estimate_candidate.source);
        }
        offer(target, along_edge, false, estimate_candidate);
      }
    }
    for (int i = stencil_start_[static_cast<size_t>(v)]; i < stencil_start_[static_cast<size_t>(v) + 1]; ++i) {
      const VirtualStencil& s = stencils_[static_cast<size_t>(stencils_by_base_[static_cast<size_t>(i)])];
      if (accepted[static_cast<size_t>(s.target)]) continue;
      const int other = s.a == v ? s.b : s.a;
      if (!accepted[static_cast<size_t>(other)]) continue;
      if (tracked_reached[static_cast<size_t>(s.target)]) continue;
      Reach through{kInfinity, s.target_corner, Vec2::Zero(), 0.0};
      through.value = two_point_update(s.position_a, s.position_b, Vec2::Zero(), dist[static_cast<size_t>(s.a)],
                                       dist[static_cast<size_t>(s.b)], through.source);
      offer(s.target, Reach{}, false, through);
    }
  }
  for (int v = 0; v < n; ++v)
    if (!accepted[static_cast<size_t>(v)]) {
      require_seed_in_every_piece(surface_pieces(d), seeds, "fast marching");
      throw InputError("fast marching: intrinsic vertex " + std::to_string(v) + " was never reached from the seeds");
    }
  return dist;
}

}  // namespace physarum
