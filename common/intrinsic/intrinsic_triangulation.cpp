#include "common/intrinsic/intrinsic_triangulation.hpp"

#include "common/base/errors.hpp"
#include "common/intrinsic/intrinsic_geometry.hpp"
#include "common/base/number_format.hpp"
#include "common/intrinsic/unfolded_walk.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <tuple>
#include <utility>

namespace physarum {

namespace {

using namespace unfolding;
constexpr double kPi = std::numbers::pi;


// How often the refinement re-scans the whole triangulation when its queues run dry, to catch
// faces missed through rounding (geometry-central does the same) without looping forever.
constexpr int kMaxRechecks = 5;

std::string where(const std::string& source) { return source.empty() ? std::string("mesh") : source; }

}  // namespace

std::string to_string(RefinementGuard guard) {
  switch (guard) {
    case RefinementGuard::NeedleVertex: return "needle vertex (angle sum < 60 degrees)";
    case RefinementGuard::UnimprovableCorner: return "unimprovable corner (between two boundary edges or at a degree-1 vertex)";
    case RefinementGuard::InsertionTooClose: return "circumcenter too close to an existing vertex";
    case RefinementGuard::TraceFailed: return "trace to the circumcenter did not finish";
    case RefinementGuard::Unresolved: return "unresolved after the final re-checks";
  }
  return "unknown";
}

// ------------------------------------------------------------------------------------------------
// Construction
// ------------------------------------------------------------------------------------------------

IntrinsicTriangulation::IntrinsicTriangulation(const InputMesh& mesh) : source_(where(mesh.source)) {
  const int nv = mesh.vertex_count();
  const int nf = mesh.triangle_count();
  input_vertex_count_ = nv;
  if (nf == 0) throw InputError(source_ + ": the mesh has no triangles");
  read_input_corners(mesh);
  match_input_twins();
  const std::vector<int> corner_count = find_input_fans(nv);
  measure_input_angles(corner_count);
  start_from_input();
}

// Corners and edge lengths.
void IntrinsicTriangulation::read_input_corners(const InputMesh& mesh) {
  const int nv = mesh.vertex_count();
  const int nf = mesh.triangle_count();
  tail_.resize(3 * static_cast<size_t>(nf));
  input_.length.resize(tail_.size());
  for (int f = 0; f < nf; ++f) {
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.triangles[f][i];
      if (v < 0 || v >= nv)
        throw InputError(source_ + ": triangle " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                         ", which does not exist (" + std::to_string(nv) + " vertices)");
      tail_[3 * f + i] = v;
    }
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.triangles[f][i], b = mesh.triangles[f][(i + 1) % 3];
      const double l = (mesh.positions[b] - mesh.positions[a]).norm();
      if (!(l > 0.0) || !std::isfinite(l))
        throw InputError(source_ + ": triangle " + std::to_string(f) + " has a zero-length or non-finite edge " +
                         std::to_string(a) + "-" + std::to_string(b));
      input_.length[3 * f + i] = l;
    }
  }
}

// Twins: sort directed edges (a, b) so that (b, a) can be found by binary search.
void IntrinsicTriangulation::match_input_twins() {
  const size_t nh = tail_.size();
  std::vector<std::pair<long long, int>> directed(nh);
  auto key = [](int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); };
  for (size_t h = 0; h < nh; ++h) directed[h] = {key(tail_[h], tail_[next(static_cast<int>(h))]), static_cast<int>(h)};
  std::sort(directed.begin(), directed.end());
  for (size_t i = 1; i < nh; ++i)
    if (directed[i].first == directed[i - 1].first) {
      const int h = directed[i].second;
      throw InputError(source_ + ": directed edge " + std::to_string(tail_[h]) + "->" +
                       std::to_string(tail_[next(h)]) + " occurs twice (triangles " +
                       std::to_string(directed[i - 1].second / 3) + " and " + std::to_string(h / 3) +
                       "): the mesh is not manifold or not consistently oriented");
    }
  input_.twin.assign(nh, -1);
  for (size_t h = 0; h < nh; ++h) {
    const long long reverse = key(tail_[next(static_cast<int>(h))], tail_[h]);
    auto it = std::lower_bound(directed.begin(), directed.end(), std::make_pair(reverse, -1));
    if (it != directed.end() && it->first == reverse) input_.twin[h] = it->second;
  }
}

// Vertex fans: the boundary vertices start at their outgoing boundary halfedge.
std::vector<int> IntrinsicTriangulation::find_input_fans(int nv) {
  const size_t nh = tail_.size();
  std::vector<int> corner_count(nv, 0);
  input_first_outgoing_.assign(nv, -1);
  vertex_is_boundary_.assign(nv, 0);
  for (size_t h = 0; h < nh; ++h) {
    const int v = tail_[h];
    ++corner_count[v];
    if (input_.twin[h] < 0) {
      if (vertex_is_boundary_[v])
        throw InputError(source_ + ": vertex " + std::to_string(v) +
                         " lies on two boundary loops (non-manifold vertex)");
      vertex_is_boundary_[v] = 1;
      input_first_outgoing_[v] = static_cast<int>(h);
    } else if (input_first_outgoing_[v] < 0) {
      input_first_outgoing_[v] = static_cast<int>(h);
    }
  }
  for (int v = 0; v < nv; ++v)
    if (corner_count[v] == 0) throw InputError(source_ + ": vertex " + std::to_string(v) + " is used by no triangle");
  return corner_count;
}

// Angle sums and signposts, walking each fan counter-clockwise: the next outgoing halfedge after
// h is twin(prev(h)).
void IntrinsicTriangulation::measure_input_angles(const std::vector<int>& corner_count) {
  const int nv = input_vertex_count_;
  input_signpost_.assign(tail_.size(), 0.0);
  vertex_angle_sum_.assign(nv, 0.0);
  const auto input_corner = [&](int h) {
    return geometry::corner_angle(input_.length[h], input_.length[prev(h)], input_.length[next(h)]);
  };
  for (int v = 0; v < nv; ++v) {
    const int first = input_first_outgoing_[v];
    int count = 0;
    double sum = 0.0;
    for (int h = first;;) {
      ++count;
      sum += input_corner(h);
      const int n = input_.twin[prev(h)];
      if (n < 0 || n == first) break;
      h = n;
      if (count > corner_count[v]) break;
    }
    if (count != corner_count[v])
      throw InputError(source_ + ": vertex " + std::to_string(v) + " has " + std::to_string(corner_count[v]) +
                       " triangles but only " + std::to_string(count) +
                       " of them form its fan (non-manifold vertex)");
    if (!(sum > 0.0))
      throw InputError(source_ + ": vertex " + std::to_string(v) + " has a zero angle sum (degenerate triangles)");
    vertex_angle_sum_[v] = sum;
    const double scale = vertex_scale(v);
    double angle = 0.0;
    for (int h = first;;) {
      input_signpost_[h] = angle;
      angle += scale * input_corner(h);
      const int n = input_.twin[prev(h)];
      if (n < 0 || n == first) break;
      h = n;
    }
  }
}

// The intrinsic triangulation starts as the input itself.
void IntrinsicTriangulation::start_from_input() {
  const int nv = input_vertex_count_;
  twin_ = input_.twin;
  length_ = input_.length;
  signpost_ = input_signpost_;
  outgoing_ = input_first_outgoing_;
  vertex_location_.resize(nv);
  for (int v = 0; v < nv; ++v) {
    const int h = input_first_outgoing_[v];
    vertex_location_[v].face = h / 3;
    vertex_location_[v].barycentric = Vector3d::Zero();
    vertex_location_[v].barycentric[h % 3] = 1.0;
  }
  input_direction_offset_.assign(nv, 0.0);
  boundary_input_halfedge_.assign(nv, -1);
  boundary_parameter_.assign(nv, 0.0);
  in_edge_queue_.assign(tail_.size(), 0);
}

// ------------------------------------------------------------------------------------------------
// Queries
// ------------------------------------------------------------------------------------------------

double IntrinsicTriangulation::vertex_scale(int v) const {
  return (vertex_is_boundary_[v] ? kPi : 2.0 * kPi) / vertex_angle_sum_[v];
}

double IntrinsicTriangulation::corner_angle_at(int h) const {
  return geometry::corner_angle(length_[h], length_[prev(h)], length_[next(h)]);
}

double IntrinsicTriangulation::face_area(int f) const {
  return geometry::triangle_area(length_[3 * f], length_[3 * f + 1], length_[3 * f + 2]);
}

double IntrinsicTriangulation::face_circumradius(int f) const {
  return geometry::circumradius(length_[3 * f], length_[3 * f + 1], length_[3 * f + 2]);
}

double IntrinsicTriangulation::face_min_angle_deg(int f) const {
  double smallest = kPi;
  for (int i = 0; i < 3; ++i) smallest = std::min(smallest, corner_angle_at(3 * f + i));
  return smallest * 180.0 / kPi;
}

double IntrinsicTriangulation::cotan_weight(int h) const {
  // cot of the angle opposite halfedge h in its face: sides next(h), prev(h), opposite h.
  const auto cot_in_face = [&](int x) { return geometry::cotan_opposite(length_[next(x)], length_[prev(x)], length_[x]); };
  double sum = cot_in_face(h);
  if (twin_[h] >= 0) sum += cot_in_face(twin_[h]);
  return 0.5 * sum;
}

bool IntrinsicTriangulation::edge_is_delaunay(int h, double tolerance) const {
  if (twin_[h] < 0) return true;
  return 2.0 * cotan_weight(h) >= -tolerance;
}

bool IntrinsicTriangulation::is_delaunay(double rel_tol) const {
  double largest = 1.0, smallest = 0.0;
  for (size_t h = 0; h < tail_.size(); ++h) {
    if (twin_[h] < 0) continue;
    const double w = cotan_weight(static_cast<int>(h));
    largest = std::max(largest, std::abs(w));
    smallest = std::min(smallest, w);
  }
  return smallest >= -rel_tol * largest;
}

double IntrinsicTriangulation::min_angle_deg() const {
  double smallest = 180.0;
  for (int f = 0; f < face_count(); ++f) smallest = std::min(smallest, face_min_angle_deg(f));
  return smallest;
}

double IntrinsicTriangulation::max_circumradius() const {
  double largest = 0.0;
  for (int f = 0; f < face_count(); ++f) largest = std::max(largest, face_circumradius(f));
  return largest;
}

double IntrinsicTriangulation::total_area() const {
  double sum = 0.0;
  for (int f = 0; f < face_count(); ++f) sum += face_area(f);
  return sum;
}

IntrinsicMesh IntrinsicTriangulation::snapshot() const {
  IntrinsicMesh out;
  out.vertex_count = vertex_count();
  const int nf = face_count();
  out.faces.resize(nf);
  out.edge_lengths.resize(nf);
  out.twin.resize(nf);
  for (int f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i) {
      out.faces[f][i] = tail_[3 * f + i];
      out.edge_lengths[f][i] = length_[3 * f + i];
      out.twin[f][i] = twin_[3 * f + i];
    }
  out.vertex_location = vertex_location_;
  return out;
}

std::string IntrinsicTriangulation::check_consistency() const {
  const int nh = static_cast<int>(tail_.size());
  for (int h = 0; h < nh; ++h) {
    const int t = twin_[h];
    if (t >= 0) {
      if (twin_[t] != h) return "twin of twin " + std::to_string(h);
      if (tail_[t] != head(h) || head(t) != tail_[h]) return "twin endpoints " + std::to_string(h);
      if (length_[t] != length_[h]) return "twin lengths " + std::to_string(h);
    }
  }
  for (int v = 0; v < vertex_count(); ++v) {
    const int first = outgoing_[v];
    if (tail_[first] != v) return "outgoing tail " + std::to_string(v);
    if (vertex_is_boundary_[v] && twin_[first] >= 0) return "boundary outgoing " + std::to_string(v);
    double sum = 0.0;
    int count = 0;
    for (int h = first;;) {
      const double c = corner_angle_at(h);
      const int n = twin_[prev(h)];
      if (n < 0 || n == first) {
        sum += c;
        // The last wedge ends at pi on a boundary, or comes back to the first signpost inside.
        const double end = signpost_[h] + vertex_scale(v) * c;
        const double gap = vertex_is_boundary_[v] ? std::abs(end - kPi)
                                                  : std::abs(geometry::wrap_angle(end - signpost_[first] + 1.0) - 1.0);
        if (gap > 1e-6)
          return "signposts do not close at " + std::to_string(v) + ": " + std::to_string(end);
        break;
      }
      const double expected = signpost_[h] + vertex_scale(v) * c;
      if (std::abs(geometry::wrap_angle(expected) - signpost_[n]) > 1e-6 &&
          std::abs(std::abs(geometry::wrap_angle(expected) - signpost_[n]) - 2 * kPi) > 1e-6)
        return "signpost step at " + std::to_string(v) + " halfedge " + std::to_string(n) + ": " +
               std::to_string(expected) + " vs " + std::to_string(signpost_[n]);
      sum += c;
      h = n;
      if (++count > 100000) return "fan does not close " + std::to_string(v);
    }
    if (std::abs(sum - vertex_angle_sum_[v]) > 1e-6) return "angle sum " + std::to_string(v) + ": " + std::to_string(sum) + " vs " + std::to_string(vertex_angle_sum_[v]);
  }
  return {};
}

// ------------------------------------------------------------------------------------------------
// Edge flips
// ------------------------------------------------------------------------------------------------

// After faces were rewritten, the halfedges that survive (outer edges of the rewritten faces) have
// new slots: old_halfedges[i] moved to new_halfedges[i] for i < surviving; their twins (outside or
// inside the rewritten faces) are re-pointed. Pairs from `surviving` to `count` name removed
// halfedges and the replacement used for vertices whose outgoing halfedge was one of them. The new
// slots' own twin entries must still hold the OLD twins when this is called; every map is applied
// exactly once, because old and new slot numbers overlap.
void IntrinsicTriangulation::remap_after_rewrite(const int* old_halfedges, const int* new_halfedges, int surviving,
                                                 int count) {
  const auto map = [&](int x, int n) {
    for (int i = 0; i < n; ++i)
      if (old_halfedges[i] == x) return new_halfedges[i];
    return x;
  };
  for (int i = 0; i < surviving; ++i) {
    const int x = new_halfedges[i];
    twin_[x] = twin_[x] < 0 ? -1 : map(twin_[x], surviving);
  }
  for (int i = 0; i < surviving; ++i) {
    const int x = new_halfedges[i];
    if (twin_[x] >= 0) twin_[twin_[x]] = x;
  }
  int done[8];
  int n_done = 0;
  for (int i = 0; i < count; ++i) {
    const int v = tail_[new_halfedges[i]];
    if (std::find(done, done + n_done, v) != done + n_done) continue;
    done[n_done++] = v;
    outgoing_[v] = map(outgoing_[v], count);
  }
}

bool IntrinsicTriangulation::flip_edge(int h) {
  const int t = twin_[h];
  if (t < 0) return false;  // boundary edges are never flipped
  const int f = h / 3, g = t / 3;
  if (f == g) return false;  // an edge glued to its own face (degree-1 vertex): no quad to flip in
  const int h_bc = next(h), h_ca = prev(h), h_ad = next(t), h_db = prev(t);
  const int a = tail_[h], b = tail_[t], c = tail_[h_ca], d = tail_[h_db];
  const double l_ab = length_[h], l_bc = length_[h_bc], l_ca = length_[h_ca], l_ad = length_[h_ad],
               l_db = length_[h_db];

  // The quad (a, d, b, c) must be strictly convex at a and b, or the new diagonal would leave it.
  const double angle_a = geometry::corner_angle(l_ab, l_ca, l_bc) + geometry::corner_angle(l_ab, l_ad, l_db);
  const double angle_b = geometry::corner_angle(l_ab, l_bc, l_ca) + geometry::corner_angle(l_ab, l_db, l_ad);
  if (!(angle_a < kPi - 1e-12) || !(angle_b < kPi - 1e-12)) return false;

  // New diagonal length from a planar layout of the quad: c above a->b, d below.
  const Vector2d pa(0.0, 0.0), pb(l_ab, 0.0);
  const Vector2d pc = geometry::layout_third_corner(pa, pb, l_ab, l_ca, l_bc);
  const Vector2d pd = geometry::layout_third_corner(pb, pa, l_ab, l_db, l_ad);
  const double l_cd = (pc - pd).norm();
  // Guard: both new triangles must be non-degenerate (strict triangle inequality).
  if (!(l_cd > 0.0) || geometry::triangle_area(l_ca, l_ad, l_cd) <= 0.0 ||
      geometry::triangle_area(l_db, l_bc, l_cd) <= 0.0)
    return false;

  const double sp_bc = signpost_[h_bc], sp_ca = signpost_[h_ca], sp_ad = signpost_[h_ad], sp_db = signpost_[h_db];
  const double sp_cd = geometry::wrap_angle(sp_ca + vertex_scale(c) * geometry::corner_angle(l_ca, l_cd, l_ad));
  const double sp_dc = geometry::wrap_angle(sp_db + vertex_scale(d) * geometry::corner_angle(l_db, l_cd, l_bc));

  // New faces: f = (c, a, d), g = (d, b, c); the diagonal is 3f+2 (d->c) / 3g+2 (c->d).
  const int twin_bc = twin_[h_bc], twin_ca = twin_[h_ca], twin_ad = twin_[h_ad], twin_db = twin_[h_db];
  set_halfedge(3 * f + 0, c, l_ca, sp_ca, twin_ca);
  set_halfedge(3 * f + 1, a, l_ad, sp_ad, twin_ad);
  set_halfedge(3 * f + 2, d, l_cd, sp_dc, 3 * g + 2);
  set_halfedge(3 * g + 0, d, l_db, sp_db, twin_db);
  set_halfedge(3 * g + 1, b, l_bc, sp_bc, twin_bc);
  set_halfedge(3 * g + 2, c, l_cd, sp_cd, 3 * f + 2);
  // The flipped edge itself is interior, so it is never a boundary vertex's reference halfedge; a
  // vertex that used it as its entry point gets its other edge in the new faces.
  const int old_slots[6] = {h_ca, h_ad, h_db, h_bc, h, t};
  const int new_slots[6] = {3 * f + 0, 3 * f + 1, 3 * g + 0, 3 * g + 1, 3 * f + 1, 3 * g + 1};
  remap_after_rewrite(old_slots, new_slots, 4, 6);
  ++flip_count_;
  return true;
}

void IntrinsicTriangulation::enqueue_edge(int h) {
  if (in_edge_queue_[h]) return;
  const int t = twin_[h];
  if (t < 0) return;
  if (in_edge_queue_[t]) return;
  in_edge_queue_[h] = 1;
  edge_queue_.push_back(h);
}

size_t IntrinsicTriangulation::flip_queued_edges(std::vector<int>* touched_faces) {
  size_t flips = 0;
  // FIFO over a vector: edge_queue_ only grows while this runs; consumed entries are dropped at the end.
  for (size_t head_index = 0; head_index < edge_queue_.size(); ++head_index) {
    const int h = edge_queue_[head_index];
    in_edge_queue_[h] = 0;
    if (edge_is_delaunay(h, kDelaunayTolerance)) continue;
    const int g = twin_[h] / 3, f = h / 3;
    if (!flip_edge(h)) continue;
    ++flips;
    for (const int x : {3 * f + 0, 3 * f + 1, 3 * g + 0, 3 * g + 1}) enqueue_edge(x);
    if (touched_faces) {
      touched_faces->push_back(f);
      touched_faces->push_back(g);
    }
  }
  edge_queue_.clear();
  return flips;
}

size_t IntrinsicTriangulation::flip_to_delaunay() {
  size_t flips = 0;
  // A full pass re-checks every edge: flips that a guard refused earlier may become possible after
  // their neighbours changed. A few passes suffice; each is O(edges) when nothing is left.
  for (int pass = 0; pass < kMaxRechecks; ++pass) {
    for (size_t h = 0; h < tail_.size(); ++h)
      if (twin_[h] > static_cast<int>(h)) enqueue_edge(static_cast<int>(h));
    const size_t done = flip_queued_edges(nullptr);
    flips += done;
    if (done == 0) break;
  }
  return flips;
}

}  // namespace physarum
